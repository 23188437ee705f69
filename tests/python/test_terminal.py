"""What the CLI says: a progress line of `impactfe run` on a terminal only, never wider than
the terminal; Ctrl-C (SIGINT) and SIGTERM stop a run cleanly (exit 130 / 143, the results file
marked "interrupted", a restart point it continues from); the run summary with the energy balance
in the job's log as well as on stdout, and `post --freq` on a file without modes as an error."""
import fcntl
import os
import pty
import re
import select
import signal
import struct
import subprocess
import termios
import time

import h5py
import numpy as np
import pytest

import impactfe

from conftest import DECKS, run

# A transient long enough to draw the line more than once (10 lines/s at most), small enough to
# run in a few seconds: the initial-velocity verification deck at a finer step.
DECK = os.path.join(DECKS, "..", "verification", "initial_velocity.inp")


def _deck(tmp_path, substeps):
    text = open(DECK).read().replace("DELTIM,1E-3", f"DELTIM,{0.5 / substeps:.6g}")
    text = text.replace("OUTRES,ALL,ALL", "OUTRES,ALL,LAST")  # progress, not output, is tested
    path = tmp_path / "progress.inp"
    path.write_text(text)
    return str(path)


def _run_on_terminal(binary, deck, out, columns=200, env=None):
    """Runs impactfe with stderr on a pseudo-terminal `columns` wide (None: no size set);
    returns (exit status, what the terminal got)."""
    master, slave = pty.openpty()
    if columns:
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, columns, 0, 0))
    p = subprocess.Popen([binary, "run", deck, "-o", out], stdout=subprocess.DEVNULL,
                         stderr=slave, stdin=subprocess.DEVNULL, env=env)
    os.close(slave)
    got = b""
    while True:
        ready, _, _ = select.select([master], [], [], 0.2)
        if ready:
            try:
                chunk = os.read(master, 65536)
            except OSError:  # the child closed the terminal
                break
            if not chunk:
                break
            got += chunk
        elif p.poll() is not None:
            break
    os.close(master)
    return p.wait(), got.decode(errors="replace")


# Substeps of a run drawn several times with an estimate (a second or more of stepping; the first
# line has none: the pace is measured from the first substep on).
DRAWN = 1000000


def _lines(text):
    return [s for s in text.split("\r\x1b[K") if s]


def _seconds(duration):
    """Seconds of a drawn duration: "12.3 s", "2:05 min" or "1.5 h"."""
    value, unit = duration.split()
    if unit == "min":
        minutes, seconds = value.split(":")
        return 60 * int(minutes) + int(seconds) + 1  # the seconds are truncated
    return float(value) * (3600 if unit == "h" else 1) + 0.1


def test_progress_line_on_a_terminal(binary, tmp_path):
    deck = _deck(tmp_path, DRAWN)
    status, text = _run_on_terminal(binary, deck, str(tmp_path / "tty"))
    assert status == 0, text
    lines = _lines(text)
    assert lines, "nothing drawn on the terminal"
    pat = re.compile(r"full transient \(Newmark\) \| t (\S+)/0\.5 \| load step 1 substep "
                     r"(\d+)/1000000 \| dt 5e-07 \| (\d+) iter \| 0 status changes \| "
                     r"\S+ (?:s|min|h) elapsed")
    seen = [pat.match(s) for s in lines]
    assert all(seen), lines
    times = [float(m.group(1)) for m in seen]
    steps = [int(m.group(2)) for m in seen]
    assert times == sorted(times) and steps == sorted(steps)
    assert steps[-1] == DRAWN and abs(times[-1] - 0.5) < 1e-9  # the last substep is drawn
    assert all(int(m.group(3)) >= 1 for m in seen)
    assert any(re.search(r" \| ~\S+ (s|min|h) left to t 0\.5$", s) for s in lines[:-1])
    # At most 10 redraws a second of the run's own clock (the last line's elapsed time), plus the
    # first and the last line: a bound that holds on a slow machine or under the sanitizers.
    elapsed = _seconds(re.search(r"\| (\S+ (?:s|min|h)) elapsed", lines[-1]).group(1))
    assert len(lines) <= 10 * elapsed + 3, "the line is redrawn at most 10 times a second"
    assert text.endswith("\r\x1b[K"), "the line is cleared at the end"


def test_progress_line_fits_the_terminal(binary, tmp_path):
    """One line, never wrapped: at most the terminal's columns less one (80, 100 wide), $COLUMNS
    when the terminal has no size, else 100; the time reached and the time left are kept."""
    deck = _deck(tmp_path, DRAWN)
    env = {k: v for k, v in os.environ.items() if k != "COLUMNS"}
    cases = [(80, env, 79), (100, env, 99), (None, env, 99), (None, dict(env, COLUMNS="60"), 59)]
    for k, (columns, environment, width) in enumerate(cases):
        status, text = _run_on_terminal(binary, deck, str(tmp_path / f"w{k}"), columns,
                                        environment)
        assert status == 0, text
        lines = _lines(text)
        assert lines and all(len(s) <= width for s in lines), (columns, width, lines)
        assert all(s.startswith(("full transient", "t ")) for s in lines), lines
        assert any("left" in s for s in lines[:-1]), lines


def test_progress_estimate_covers_every_known_load_step(binary, tmp_path):
    """LSSOLVE hands its load steps over at once: while load step 1 runs, the time left is
    estimated to the end of load step 2."""
    text = open(_deck(tmp_path, DRAWN)).read()
    text = text.replace("TIME,0.5\n", "TIME,0.25\n").replace(
        "SOLVE\n", "LSWRITE,1\nTIME,0.5\nLSWRITE,2\nLSSOLVE,1,2\n")
    deck = tmp_path / "lssolve.inp"
    deck.write_text(text)
    status, text = _run_on_terminal(binary, str(deck), str(tmp_path / "ls"))
    assert status == 0, text
    lines = _lines(text)
    first = [s for s in lines if "load step 1 " in s and "left" in s]
    assert first, lines
    assert all("left to t 0.5" in s for s in first), first


def test_progress_line_of_a_reduced_transient(binary, tmp_path):
    """The reduced (Guyan) transient reports its steps too; it does not count gap status changes,
    so the line leaves them out rather than printing 0."""
    deck = os.path.join(DECKS, "modern", "crash1_modern.inp")
    status, text = _run_on_terminal(binary, deck, str(tmp_path / "reduced"))
    assert status == 0, text
    lines = [s for s in _lines(text) if s.startswith("transient (reduced")]
    assert lines, text
    assert all(re.match(r"transient \(reduced, \w+\) \| t \S+/\S+ \| load step \d+ substep "
                        r"\d+/\d+ \| dt \S+ \| 1 iter \| \S+ s elapsed", s) for s in lines), lines
    assert "status changes" not in "".join(lines)


def test_progress_line_of_an_explicit_run(binary, tmp_path):
    """An explicit (central difference) run shows its cycles, time step and energy error, within
    an 80-column terminal; the last line is the end of the run."""
    text = open(os.path.join(DECKS, "..", "verification", "explicit_bar_wave_solid164.inp")).read()
    deck = tmp_path / "wave.inp"
    deck.write_text(text.replace("TIME,3.0E-4", "TIME,1.0E-2"))  # about a second of cycles
    status, text = _run_on_terminal(binary, str(deck), str(tmp_path / "explicit"), columns=80)
    assert status == 0, text
    lines = [s for s in _lines(text) if s.startswith(("explicit dynamics", "t "))]
    assert len(lines) >= 2, text
    assert all(len(s) <= 79 for s in lines), lines
    pat = re.compile(r"(explicit dynamics \| )?t (\S+)/0\.01 \| (ls 1 |load step 1 )?cycle (\d+)"
                     r"( \| dt \S+)?( \| (energy error|err) \S+ %)?")
    seen = [pat.match(s) for s in lines]
    assert all(seen), lines
    cycles = [int(m.group(4)) for m in seen]
    assert cycles == sorted(cycles) and cycles[-1] > cycles[0], lines
    assert abs(float(seen[-1].group(2)) - 0.01) < 1e-12, lines[-1]
    assert any("err" in s for s in lines), lines
    assert "iter" not in "".join(lines) and "chg" not in "".join(lines)


def test_no_progress_line_without_a_terminal(binary, tmp_path):
    deck = _deck(tmp_path, 2000)
    p = run([binary, "run", deck, "-o", str(tmp_path / "pipe")])
    assert "\r" not in p.stderr and "substep" not in p.stderr, p.stderr


def test_summary_and_energy_in_the_log(binary, tmp_path):
    deck = _deck(tmp_path, 500)
    out = tmp_path / "log"
    p = run([binary, "run", deck, "-o", str(out)])
    log = (out / "progress.log").read_text()
    energy = re.search(r"energy at t = 0\.5: .*", p.stdout).group(0)
    assert energy in log  # the same line, word for word
    assert "initial kinetic 50" in energy
    assert "run summary:" in log and "full transient (Newmark): 1 DOFs" in log


def test_post_freq_without_modes_is_an_error(binary, tmp_path):
    """`post --freq` / `--mode` on a file without a modal analysis: exit 1 and a message, never a
    bare CSV header with exit 0."""
    out = tmp_path / "nomodes"
    run([binary, "run", _deck(tmp_path, 50), "-o", str(out)])
    results = str(out / "progress.h5")
    p = run([binary, "post", results, "--freq"], expect=1)
    assert p.stdout == "" and "holds no modal results" in p.stderr, p.stderr
    p = run([binary, "post", results, "--mode", "1"], expect=1)
    assert p.stdout == "" and "no mode shapes" in p.stderr, p.stderr


def test_mp_damp_refused_where_it_is_not_applied(binary, tmp_path):
    """MP,DAMP in a reduced transient (which forms C from ALPHAD/BETAD only) is an input error
    naming the element's deck line, not a damping silently dropped."""
    deck = os.path.join(os.path.dirname(os.path.abspath(__file__)), "decks",
                        "mp_damp_reduced_transient.inp")
    p = run([binary, "run", deck, "-o", str(tmp_path)], expect=1)
    assert "mp_damp_reduced_transient.inp:12: E: element 1: its material 1 has MP,DAMP" in p.stderr, \
        p.stderr
    assert "BETAD" in p.stderr


def test_version_names_the_version_and_the_commit(binary):
    """`impactfe --version`: the project version and the commit the program was built from."""
    p = run([binary, "--version"])
    assert re.fullmatch(r"impactfe \d+\.\d+\.\d+ \(([0-9a-f]{7,40}(-dirty)?|unknown)\)\n", p.stdout), \
        p.stdout


def test_command_line_errors_exit_1_with_the_usage_line(binary):
    """A command-line error (unknown option, missing argument, no subcommand) exits 1, the
    documented status of bad input, with CLI11's message and the usage line."""
    for args in (["run"], ["run", "deck.inp", "--no-such-option"], [], ["post"],
                 ["run", "deck.inp", "--dialect", "5x"]):
        p = run([binary] + args, expect=1)
        assert p.stderr.startswith("error: ") and "usage: impactfe" in p.stderr, (args, p.stderr)
    assert run([binary, "run", "--help"]).stdout.startswith("run an APDL deck")
    # The usage line names every subcommand of --help; a word that is none is said to be none.
    listed = re.search(r"Subcommands:\n((?:  \S+ .*\n)+)", run([binary, "--help"]).stdout)
    names = [line.split()[0] for line in listed.group(1).splitlines()]
    assert "mesh" in names, names
    p = run([binary, "frobnicate", "x.inp"], expect=1)
    assert p.stderr.startswith("error: 'frobnicate' is not a subcommand of impactfe\n"), p.stderr
    assert f"usage: impactfe {{{'|'.join(names)}}} ..." in p.stderr, p.stderr


def _interrupt(binary, deck, out, sig, jobname="progress"):
    """Starts the run, waits until it has stored steps, sends `sig`; returns the process."""
    p = subprocess.Popen([binary, "run", deck, "-o", out, "-j", jobname],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    results = os.path.join(out, jobname + ".h5")
    deadline = time.monotonic() + 60
    while not os.path.exists(results) and time.monotonic() < deadline and p.poll() is None:
        time.sleep(0.05)
    time.sleep(0.5)  # inside the stepping (a substep takes microseconds: 10 s in all)
    assert p.poll() is None, "the run ended before it could be interrupted: make it longer"
    p.send_signal(sig)
    stdout, stderr = p.communicate(timeout=120)
    return p.returncode, stdout, stderr


LONG = 1000000  # substeps of 0.5 us: some seconds of stepping, interrupted after half a second


def _long_deck(tmp_path):
    deck = _deck(tmp_path, LONG)
    text = open(deck).read().replace("OUTRES,ALL,LAST", "OUTRES,ALL,10000")  # 100 points
    open(deck, "w").write(text)
    return deck


@pytest.mark.parametrize("sig,status", [(signal.SIGINT, 130), (signal.SIGTERM, 143)])
def test_interrupted_run_stops_cleanly(binary, tmp_path, sig, status):
    """Ctrl-C (SIGINT) or SIGTERM: the substep being solved is finished, its state kept as a
    restart point, the analysis marked "interrupted"; exit 128 + the signal; the file reads."""
    out = tmp_path / "stop"
    code, stdout, stderr = _interrupt(binary, _long_deck(tmp_path), str(out), sig)
    assert code == status, stderr
    name = "SIGINT" if sig == signal.SIGINT else "SIGTERM"
    assert "stopping after the current substep" in stderr, stderr
    # The message names what came (Ctrl-C only for SIGINT); off a terminal no empty line.
    received = "interrupt received" if sig == signal.SIGINT else "SIGTERM received"
    assert f"impactfe: {received}: stopping" in stderr, stderr
    assert ("Ctrl-C" in stderr) == (sig == signal.SIGINT), stderr
    assert "\n\n" not in stderr and not stderr.startswith("\n"), repr(stderr)
    m = re.search(rf"impactfe: interrupted by {name} at t = (\S+) \(load step 1, substep "
                  r"(\d+)\)", stderr)
    assert m, stderr
    assert abs(float(m.group(1)) - int(m.group(2)) * 0.5 / LONG) < 1e-6
    assert "results up to the interruption are kept in" in stderr and '"interrupted"' in stderr
    log = (out / "progress.log").read_text()
    assert f"interrupted by {name}" in log and f"exit status {status}" in log
    with h5py.File(out / "progress.h5", "r") as f:
        assert f["analysis_1"].attrs["status"] == b"interrupted"
    r = impactfe.open(str(out / "progress.h5"))
    assert r.analyses()["status"].tolist() == ["interrupted"]
    ux = r.history(node=2, item="UX")
    assert len(ux) >= 2 and ux.index[0] == 0.0
    t = ux.index.values
    np.testing.assert_allclose(ux.iloc[:, 0].values, np.sin(10 * t), atol=1e-6)
    assert os.path.exists(out / "progress.rst.h5")


def test_interrupted_run_continues_from_its_restart_point(binary, tmp_path):
    """ANTYPE,,RESTART after Ctrl-C continues from the last converged substep to the answer of
    the run that was not interrupted, to round-off."""
    deck = _long_deck(tmp_path)
    reference = run([binary, "run", deck, "-o", str(tmp_path / "whole"), "-j", "progress"])
    assert "interrupted" not in reference.stderr
    whole = impactfe.open(str(tmp_path / "whole" / "progress.h5")).history(node=2, item="UX")
    out = tmp_path / "again"
    code, _, stderr = _interrupt(binary, deck, str(out), signal.SIGINT)
    assert code == 130, stderr
    stopped_at = float(re.search(r"interrupted by SIGINT at t = (\S+)", stderr).group(1))
    assert 0 < stopped_at < 0.5
    cont = tmp_path / "continue.inp"
    cont.write_text(open(deck).read().replace("SOLVE\n", "ANTYPE,TRANS,RESTART\nSOLVE\n"))
    p = run([binary, "run", str(cont), "-o", str(out), "-j", "progress"])
    assert "continued from the restart point of load step 1 substep" in p.stdout
    r = impactfe.open(str(out / "progress.h5"))
    assert r.analyses()["status"].tolist() == ["interrupted", "complete"]
    ux = r.history(node=2, item="UX")
    assert ux.index[-1] == pytest.approx(0.5) and len(ux) == len(whole)
    np.testing.assert_allclose(ux.iloc[:, 0].values, whole.iloc[:, 0].values, rtol=0, atol=1e-12)


def test_second_interrupt_stops_at_once_and_keeps_the_flushed_results(binary, tmp_path):
    """Two Ctrl-Cs in a row: the second one, while the first is still being carried out
    (finishing the substep, writing the restart point), stops the run at once with exit 130 and
    says so; the results file keeps what was flushed before and reads."""
    deck = _long_deck(tmp_path)
    out = tmp_path / "twice"
    p = subprocess.Popen([binary, "run", deck, "-o", str(out), "-j", "progress"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    results = out / "progress.h5"
    deadline = time.monotonic() + 60
    while not results.exists() and time.monotonic() < deadline and p.poll() is None:
        time.sleep(0.05)
    time.sleep(0.5)
    assert p.poll() is None, "the run ended before it could be interrupted: make it longer"
    p.send_signal(signal.SIGINT)
    p.send_signal(signal.SIGINT)
    _, stderr = p.communicate(timeout=120)
    assert p.returncode == 130, stderr
    # Either the second signal arrived while the first was being carried out (stopped at once),
    # or after the run had already stopped cleanly; both must leave a readable file.
    assert ("stopped at once (second interrupt)" in stderr
            or "results up to the interruption are kept in" in stderr), stderr
    r = impactfe.open(str(results))
    ux = r.history(node=2, item="UX")
    assert len(ux) >= 1 and ux.index[0] == 0.0

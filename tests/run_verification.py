#!/usr/bin/env python3
"""Runs one verification deck through the impactfe CLI and checks the expectations written in it.

Usage: run_verification.py IMPACTFE_BINARY DECK OUTDIR
(OUTDIR/<deck> is removed when every expectation is met, unless IMPACTFE_KEEP_TEST_OUTPUT is set.)

Expectation lines in the deck (comments, so the deck stays a valid APDL deck):
  ! EXPECT: NSOL <node> <LAB> AT <time> = <value> TOL <abs>      nodal result at a stored time
  ! EXPECT: RSOL <node> <LAB> AT <time> = <value> TOL <abs>      reaction force (LAB = FX..MZ)
  ! EXPECT: ESOL <elem> <ITEM> AT <time> = <value> TOL <abs>     element result
  ! EXPECT: MAX|MIN NSOL|ESOL <id> <LAB> = <value> TOL <abs>     extreme over all stored times
  ! EXPECT: TIMEOF MAX|MIN NSOL|ESOL <id> <LAB> = <time> TOL <abs>
  ! EXPECT: FIRST ESOL <id> <ITEM> <op> <threshold> AT = <time> TOL <abs>
        first stored time at which the item satisfies op (GE, LE) the threshold
  ! EXPECT: FREQ <mode> = <hz> RTOL <rel>                         modal frequency
  ! EXPECT: EXIT <status>                                         exit status of the run
  ! EXPECT: FILE <name> COLUMN <j> = <value> TOL|RTOL <tol>       every row of the text file
        <name> (written by the deck in its working directory, e.g. through /OUT or *CFOPEN)
        whose whitespace-separated token j (1-based) is a number: that number (e.g. a ratio
        column of a *VWRITE target / computed / ratio table); at least one such row
  ! EXPECT: FILE <name> ROW <i> COLUMN <j> = <value> TOL|RTOL <tol>   the i-th such row only
  ! EXPECT: FILE <name> ROWS <n>                                  number of rows with a number
        in their first token
  ! EXPECT: FILE <name> LINE <n> IS <text>                        line n is <text> (trailing
        blanks are not compared)
  ! EXPECT: STDOUT CONTAINS <text>                                the run printed <text>
  ! EXPECT: WARNING <text>      the run warned with <text> on stderr and in <job>.log
  ! EXPECT: NOWARNING <text>    no warning containing <text>
  ! EXPECT: LOG <text>          <job>.log contains <text> (e.g. the run summary)
`AT <time>` picks the stored point nearest to <time> (within 1e-9 relative), or interpolates
linearly between stored points when the time lies between them.
"""
import csv
import io
import os
import re
import shutil
import subprocess
import sys


def fail(msg):
    print("FAIL: " + msg)
    sys.exit(1)


def post(binary, h5, args):
    r = subprocess.run([binary, "post", h5] + args, capture_output=True, text=True)
    if r.returncode != 0:
        fail("impactfe post %s: %s" % (" ".join(args), r.stderr.strip()))
    rows = list(csv.reader(io.StringIO(r.stdout)))
    return rows[0], [[float(x) if x else float("nan") for x in row] for row in rows[1:]]


def series(binary, h5, kind, ident, lab):
    flag = {"NSOL": "--nsol", "RSOL": "--nsol", "ESOL": "--esol"}[kind]
    _, rows = post(binary, h5, [flag, "%s,%s" % (ident, lab)])
    return [(r[0], r[1]) for r in rows if r[1] == r[1]]


def value_at(points, t):
    if not points:
        fail("no stored values")
    for (t0, v0) in points:
        if abs(t0 - t) <= 1e-9 * max(1.0, abs(t)):
            return v0
    for (t0, v0), (t1, v1) in zip(points, points[1:]):
        if t0 <= t <= t1:
            return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    fail("time %g outside the stored range [%g, %g]" % (t, points[0][0], points[-1][0]))


def check(name, got, want, tol, rel=False):
    bound = tol * abs(want) if rel else tol
    ok = abs(got - want) <= bound
    print("%s %s: got %.10g, expected %.10g (%s %g)" %
          ("ok  " if ok else "FAIL", name, got, want, "rtol" if rel else "tol", tol))
    return ok


def number(token):
    try:
        return float(token)
    except ValueError:
        return None


def numeric_rows(path, column):
    """Rows of a text file whose token `column` (1-based) is a number, as (line, value)."""
    if not os.path.exists(path):
        fail("file %s was not written" % path)
    rows = []
    with open(path) as f:
        for line in f:
            tok = line.split()
            if len(tok) >= column and number(tok[column - 1]) is not None:
                rows.append((line.rstrip("\n"), number(tok[column - 1])))
    return rows


def check_file(e, work, stdout):
    """FILE / STDOUT expectations; returns True when met."""
    m = re.match(r"STDOUT\s+CONTAINS\s+(.*)$", e)
    if m:
        ok = m.group(1) in stdout
        print("%s %s" % ("ok  " if ok else "FAIL", e))
        return ok
    m = re.match(r"FILE\s+(\S+)\s+LINE\s+(\d+)\s+IS(?:\s(.*))?$", e)
    if m:
        path = os.path.join(work, m.group(1))
        if not os.path.exists(path):
            fail("file %s was not written" % path)
        lines = open(path).read().split("\n")
        n = int(m.group(2))
        got = lines[n - 1] if n <= len(lines) else None
        ok = got is not None and got.rstrip() == (m.group(3) or "").rstrip()
        print("%s %s (got %r)" % ("ok  " if ok else "FAIL", e, got))
        return ok
    m = re.match(r"FILE\s+(\S+)\s+ROWS\s+(\d+)$", e)
    if m:
        got = len(numeric_rows(os.path.join(work, m.group(1)), 1))
        ok = got == int(m.group(2))
        print("%s %s (got %d)" % ("ok  " if ok else "FAIL", e, got))
        return ok
    m = re.match(r"FILE\s+(\S+)\s+(?:ROW\s+(\d+)\s+)?COLUMN\s+(\d+)\s*=\s*(\S+)\s+(TOL|RTOL)\s+(\S+)$", e)
    if not m:
        fail("bad EXPECT line: " + e)
    name, row, column, want, tk, tol = m.groups()
    rows = numeric_rows(os.path.join(work, name), int(column))
    if not rows:
        fail("%s: no row with a number in column %s" % (name, column))
    if row:
        if int(row) > len(rows):
            fail("%s: only %d numeric rows" % (name, len(rows)))
        rows = [rows[int(row) - 1]]
    ok = True
    for line, got in rows:
        ok &= check("%s [%s]" % (e, line.strip()), got, float(want), float(tol), tk == "RTOL")
    return ok


def main():
    binary, deck, outdir = sys.argv[1], sys.argv[2], sys.argv[3]
    stem = os.path.splitext(os.path.basename(deck))[0]
    work = os.path.join(outdir, stem)
    os.makedirs(work, exist_ok=True)
    expects = []
    with open(deck) as f:
        for line in f:
            m = re.match(r"\s*!\s*EXPECT:\s*(.*)$", line)
            if m:
                expects.append(m.group(1).strip())
    if not expects:
        fail("deck %s has no EXPECT lines" % deck)
    run = subprocess.run([binary, "run", deck, "-o", work], capture_output=True, text=True)
    print(run.stdout + run.stderr)
    want_exit = 0
    for e in expects:
        m = re.match(r"EXIT\s+(\d+)$", e)
        if m:
            want_exit = int(m.group(1))
    if run.returncode != want_exit:
        fail("exit status %d, expected %d" % (run.returncode, want_exit))
    h5 = os.path.join(work, stem + ".h5")
    all_ok = True
    for e in expects:
        tok = e.split()
        if tok[0] == "EXIT":
            continue
        if tok[0] in ("FILE", "STDOUT"):
            all_ok &= check_file(e, work, run.stdout)
            continue
        if tok[0] in ("WARNING", "NOWARNING", "LOG"):
            text = e[len(tok[0]):].strip()
            with open(os.path.join(work, stem + ".log")) as f:
                log = f.read()
            if tok[0] == "LOG":
                ok = text in log
            else:
                warned = [ln for ln in run.stderr.splitlines() if ln.startswith("warning:")]
                logged = [ln for ln in log.splitlines() if ln.startswith("warning:")]
                in_err = any(text in ln for ln in warned)
                in_log = any(text in ln for ln in logged)
                ok = (in_err and in_log) if tok[0] == "WARNING" else not (in_err or in_log)
            print("%s %s" % ("ok  " if ok else "FAIL", e))
            all_ok &= ok
            continue
        if tok[0] in ("NSOL", "RSOL", "ESOL"):
            m = re.match(r"(\w+)\s+(\d+)\s+(\w+)\s+AT\s+(\S+)\s*=\s*(\S+)\s+(TOL|RTOL)\s+(\S+)$", e)
            if not m:
                fail("bad EXPECT line: " + e)
            kind, ident, lab, t, want, tk, tol = m.groups()
            got = value_at(series(binary, h5, kind, ident, lab), float(t))
            all_ok &= check(e, got, float(want), float(tol), tk == "RTOL")
        elif tok[0] in ("MAX", "MIN"):
            m = re.match(r"(MAX|MIN)\s+(\w+)\s+(\d+)\s+(\w+)\s*=\s*(\S+)\s+(TOL|RTOL)\s+(\S+)$", e)
            if not m:
                fail("bad EXPECT line: " + e)
            which, kind, ident, lab, want, tk, tol = m.groups()
            values = [v for _, v in series(binary, h5, kind, ident, lab)]
            got = max(values) if which == "MAX" else min(values)
            all_ok &= check(e, got, float(want), float(tol), tk == "RTOL")
        elif tok[0] == "TIMEOF":
            m = re.match(r"TIMEOF\s+(MAX|MIN)\s+(\w+)\s+(\d+)\s+(\w+)\s*=\s*(\S+)\s+(TOL|RTOL)\s+(\S+)$", e)
            if not m:
                fail("bad EXPECT line: " + e)
            which, kind, ident, lab, want, tk, tol = m.groups()
            pts = series(binary, h5, kind, ident, lab)
            best = (max if which == "MAX" else min)(pts, key=lambda p: p[1])
            all_ok &= check(e, best[0], float(want), float(tol), tk == "RTOL")
        elif tok[0] == "FIRST":
            m = re.match(r"FIRST\s+(\w+)\s+(\d+)\s+(\w+)\s+(GE|LE)\s+(\S+)\s+AT\s*=\s*(\S+)\s+(TOL|RTOL)\s+(\S+)$", e)
            if not m:
                fail("bad EXPECT line: " + e)
            kind, ident, lab, op, thr, want, tk, tol = m.groups()
            thr = float(thr)
            hit = [t for t, v in series(binary, h5, kind, ident, lab)
                   if (v >= thr if op == "GE" else v <= thr)]
            if not hit:
                fail("%s: never reached" % e)
            all_ok &= check(e, hit[0], float(want), float(tol), tk == "RTOL")
        elif tok[0] == "FREQ":
            m = re.match(r"FREQ\s+(\d+)\s*=\s*(\S+)\s+(TOL|RTOL)\s+(\S+)$", e)
            if not m:
                fail("bad EXPECT line: " + e)
            mode, want, tk, tol = m.groups()
            _, rows = post(binary, h5, ["--freq"])
            freqs = {int(r[0]): r[1] for r in rows}
            if int(mode) not in freqs:
                fail("mode %s not computed" % mode)
            all_ok &= check(e, freqs[int(mode)], float(want), float(tol), tk == "RTOL")
        else:
            fail("unknown EXPECT line: " + e)
    if not all_ok:
        sys.exit(1)
    # A passing case's files go (CI disk); IMPACTFE_KEEP_TEST_OUTPUT=1 keeps them.
    if not os.environ.get("IMPACTFE_KEEP_TEST_OUTPUT"):
        shutil.rmtree(work, ignore_errors=True)
    print("verification %s: all %d expectations met" % (stem, len(expects)))


if __name__ == "__main__":
    main()

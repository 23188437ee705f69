#!/usr/bin/env python3
"""Time the impactfe CLI on the thesis decks and on generated scaled models.

For each case the CLI (`impactfe run DECK -o DIR`) is run --repeat times in a fresh directory.
Recorded per case: wall time (median and min, measured around the child process, so it includes
start-up, deck reading and HDF5 output), CPU time (user + sys, median), time per substep
(median wall / substeps), peak resident memory (max over the repeats, from /usr/bin/time %M or,
without it, from getrusage(RUSAGE_CHILDREN) of a one-shot helper process), and the DOFs,
substeps and factorizations parsed from the run summary.

A case may be a chain of decks run in the same directory (superelement generation then use
pass); its figures are the sums over the chain (DOFs: the largest).

Prints a markdown table; writes bench/results/<date>.md only with --save.
Stdlib only. Example:
    python3 bench/run_benchmarks.py --repeat 5
    python3 bench/run_benchmarks.py --only helmet --repeat 3 --save
"""
import argparse
import datetime
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import generate_models  # noqa: E402

THESIS = os.path.join(ROOT, "tests", "decks", "thesis")

# (case name, [decks run in order in one directory]). The crash decks carry their /STRESS pass.
THESIS_CASES = [
    ("pendulum1", ["pendulum1.inp"]),
    ("pendulum2", ["pendulum2.inp"]),
    ("crash1+stress", ["crash1.inp"]),
    ("crash2+stress", ["crash2.inp"]),
    ("crash3+stress", ["crash3.inp"]),
    ("helmet_full", ["helmet_full.inp"]),
    ("helmet_segen", ["helmet_segen.inp"]),
    ("helmet_se (segen+use)", ["helmet_segen.inp", "helmet_use.inp"]),
]

SUMMARY_RE = re.compile(
    r"^\s+(?P<desc>.+?): (?P<dofs>\d+) DOFs, (?P<ls>\d+) load steps, (?P<sub>\d+) substeps, "
    r"(?P<it>\d+) iterations, (?P<stored>\d+) stored, (?P<fact>\d+) factorizations "
    r"\((?P<sym>\d+) symbolic\), (?P<solves>\d+) solves, (?P<chg>\d+) status changes, "
    r"(?P<secs>[0-9.]+) s$"
)
TIME_BIN = "/usr/bin/time"


def parse_summary(text):
    """Return the analyses of a run summary as a list of dicts (ints, and 'desc')."""
    out = []
    for line in text.splitlines():
        m = SUMMARY_RE.match(line)
        if m:
            d = {k: int(v) for k, v in m.groupdict().items() if k not in ("desc", "secs")}
            d["desc"] = m.group("desc")
            d["secs"] = float(m.group("secs"))
            out.append(d)
    return out


def run_once(exe, deck, workdir):
    """Run one deck; returns (wall s, cpu s, peak RSS kB or None, analyses list)."""
    stats_file = os.path.join(workdir, ".time_stats")
    cmd = [exe, "run", deck, "-o", workdir]
    use_time = os.access(TIME_BIN, os.X_OK)
    if use_time:
        cmd = [TIME_BIN, "-o", stats_file, "-f", "%M %U %S"] + cmd
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError("%s failed (exit %d):\n%s%s" % (deck, proc.returncode, proc.stdout, proc.stderr))
    rss = cpu = None
    if use_time:
        with open(stats_file) as f:
            fields = f.read().split()
        rss, cpu = int(fields[-3]), float(fields[-2]) + float(fields[-1])
    else:
        # Fallback: re-run in a helper python whose only child is the CLI, so its
        # RUSAGE_CHILDREN maximum is this run's peak.
        helper = ("import resource,subprocess,sys;subprocess.run(sys.argv[1:],stdout=subprocess.DEVNULL,"
                  "stderr=subprocess.DEVNULL);r=resource.getrusage(resource.RUSAGE_CHILDREN);"
                  "print(r.ru_maxrss,r.ru_utime+r.ru_stime)")
        o = subprocess.run([sys.executable, "-c", helper] + cmd, stdout=subprocess.PIPE, text=True)
        rss, cpu = int(o.stdout.split()[0]), float(o.stdout.split()[1])
    return wall, cpu, rss, parse_summary(proc.stdout)


def run_case(exe, decks, repeat, keep=None):
    walls, cpus, rsss = [], [], []
    analyses = []
    for r in range(repeat):
        workdir = tempfile.mkdtemp(prefix="impactfe_bench_")
        try:
            wall = cpu = 0.0
            rss = 0
            analyses = []
            for deck in decks:
                w, c, m, a = run_once(exe, deck, workdir)
                wall += w
                cpu += c or 0.0
                rss = max(rss, m or 0)
                analyses += a
            walls.append(wall)
            cpus.append(cpu)
            rsss.append(rss)
        finally:
            if keep and r == repeat - 1:
                shutil.copytree(workdir, keep, dirs_exist_ok=True)
            shutil.rmtree(workdir, ignore_errors=True)
    # Substeps of the time-integration analyses (expansion passes re-use the same steps).
    stepping = [a for a in analyses if "expansion" not in a["desc"] and "stress" not in a["desc"]]
    substeps = sum(a["sub"] for a in stepping) or sum(a["sub"] for a in analyses)
    med = statistics.median(walls)
    return {
        "wall_med": med,
        "wall_min": min(walls),
        "cpu_med": statistics.median(cpus),
        "rss_mb": max(rsss) / 1024.0,
        "dofs": max((a["dofs"] for a in analyses), default=0),
        "substeps": substeps,
        "fact": sum(a["fact"] for a in analyses),
        "per_step_ms": 1e3 * med / substeps if substeps else float("nan"),
        "analyses": "; ".join(a["desc"] for a in analyses),
    }


def table(rows):
    head = ("| case | DOFs | substeps | factorizations | wall median (s) | wall min (s) | CPU median (s) "
            "| per step (ms) | peak RSS (MB) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n")
    body = ""
    for name, r in rows:
        body += "| %s | %d | %d | %d | %.3f | %.3f | %.3f | %.3f | %.1f |\n" % (
            name, r["dofs"], r["substeps"], r["fact"], r["wall_med"], r["wall_min"], r["cpu_med"],
            r["per_step_ms"], r["rss_mb"])
    return head + body


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "impactfe"))
    ap.add_argument("--repeat", type=int, default=5)
    ap.add_argument("--sizes", choices=sorted(generate_models.SIZES), default="default",
                    help="scaled-model set (bench/generate_models.py)")
    ap.add_argument("--no-thesis", action="store_true", help="skip the thesis decks")
    ap.add_argument("--no-scaled", action="store_true", help="skip the generated models")
    ap.add_argument("--only", default="", help="run only cases whose name contains this text")
    ap.add_argument("--save", action="store_true", help="write bench/results/<date>.md")
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    if not os.access(exe, os.X_OK):
        sys.exit("impactfe executable not found: %s (build it first)" % exe)

    cases = []
    if not args.no_thesis:
        cases += [(n, [os.path.join(THESIS, d) for d in ds]) for n, ds in THESIS_CASES]
    model_dir = None
    if not args.no_scaled:
        model_dir = tempfile.mkdtemp(prefix="impactfe_models_")
        cases += [(n, [p]) for n, p in generate_models.generate(model_dir, args.sizes).items()]
    cases = [c for c in cases if args.only in c[0]]

    rows = []
    try:
        for name, decks in cases:
            print("running %-24s x%d ..." % (name, args.repeat), file=sys.stderr, flush=True)
            r = run_case(exe, decks, args.repeat)
            rows.append((name, r))
            print("  median %.3f s  (%s)" % (r["wall_med"], r["analyses"]), file=sys.stderr, flush=True)
    finally:
        if model_dir:
            shutil.rmtree(model_dir, ignore_errors=True)

    git = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True).stdout.strip()
    header = "impactfe %s, %s, %s, %d CPUs, %d repeats, %s\n\n" % (
        git or "?", platform.node(), platform.processor() or platform.machine(), os.cpu_count() or 0,
        args.repeat, datetime.datetime.now().isoformat(timespec="seconds"))
    text = header + table(rows)
    print(text)
    if args.save:
        os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
        path = os.path.join(HERE, "results", datetime.date.today().isoformat() + ".md")
        with open(path, "w") as f:
            f.write("# impactfe benchmark run\n\n" + text)
        print("written " + path, file=sys.stderr)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The impactfe benchmark suite: thesis decks, generated scaled models and the block drop,
with the linear-solver figures, the memory-bandwidth floor and (opt-in) CalculiX side by side.

One command, stdlib only (docs/benchmarks.md explains every column):
    python3 bench/run_benchmarks.py                       # default set, 3 repeats, --threads 1
    python3 bench/run_benchmarks.py --sizes large         # adds 5.6x10^4 and 2.5x10^5 DOF block drops
    python3 bench/run_benchmarks.py --sizes huge --repeat 1   # the 10^6 DOF block drop only
    python3 bench/run_benchmarks.py --compare             # + CalculiX and the thread modes
    python3 bench/run_benchmarks.py --sizes smoke --repeat 1 --check   # the CI smoke test

Per case the CLI (`impactfe run DECK -o DIR`) runs --repeat times in a fresh directory, under
/usr/bin/time (or getrusage of a helper process without it). Recorded: process wall time
(median, min) and CPU time (user + sys, median), peak resident memory (max over repeats), and
from the run summary: DOFs, substeps, factorizations, solves, nnz(K), nnz(L), bytes of the
factor and the solver's analyze / factorize / solve times (medians). Derived:
  per step   = median process wall / substeps (start-up, deck reading and output included);
  step       = (stepping wall - analyze - factorize) / substeps: the time of a step beyond the
               factorizations (the stepping walls are those printed in the run summary; for
               analyses that print none, the analysis walls);
  floor      = 2 * bytes(L) / B, B = one-thread STREAM triad bandwidth measured by
               bench_memory in the same run (best of the measurements before and after the
               cases: the higher the bandwidth, the lower and safer the floor);
  step/floor = step / floor;
  ms/solve   = solve time / solves, and solve/floor = ms/solve / floor (the solver alone).
A case may be a chain of decks run in the same directory (superelement generation, then use
pass); its figures are the sums over the chain (DOFs and sizes: the largest).

--compare adds, for the block drops of the chosen set up to --compare-max-dofs: CalculiX (`ccx`,
Debian package calculix-ccx) on the same model, and impactfe with --threads 1, with default
threads, and both again while one `yes >/dev/null` process keeps a core busy. It reports wall
and CPU times (medians), their ratios to CalculiX, and the agreement of the monitored history
(corner node UZ): max |difference| over the common output times / max |UZ|, required <= 0.5 %.

Prints markdown tables; --save also writes bench/results/<date>-<sizes>.md and .json.
"""
import argparse
import datetime
import json
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
import gen_blockdrop  # noqa: E402
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

# Block drops (bench/gen_blockdrop.py): (NX, NY, NZ, dt). dt = 1e-5 s is the published model
# (3000 steps to t = 0.03 s); the large ones use dt = 1e-4 s (300 steps, the block still lands at
# t = 16 ms and bounces) so that a run takes minutes, not hours; compare their per-step times.
# DOFs = 3 (NX+1)(NY+1)(NZ+1).
BLOCKDROP_SIZES = {
    "smoke": [(4, 4, 2, 1e-4)],
    "small": [(4, 4, 2, 1e-5), (8, 8, 4, 1e-5)],
    "default": [(8, 8, 4, 1e-5), (16, 16, 8, 1e-5)],
    # 55 539 DOFs as a 2:2:1 brick, 249 615 DOFs as a slab (NZ = 4): minutes each. 105 903 DOFs
    # as a 2:2:1 brick: its 1 681 gap DOFs are the largest set the condensed transient takes.
    "large": [(8, 8, 4, 1e-5), (16, 16, 8, 1e-5), (32, 32, 16, 1e-4), (40, 40, 20, 1e-4),
              (128, 128, 4, 1e-4)],
    # 990 735 DOFs, a slab: a factor of several GB and about an hour with the reference BLAS.
    # (A 2:2:1 brick of 10^6 DOFs has a factor of tens of GB: beyond this machine.)
    "huge": [(256, 256, 4, 1e-4)],
}
# generate_models.py sets for each --sizes value (None: none of those models).
SCALED_SET = {"smoke": "smoke", "small": "small", "default": "default", "large": "large",
              "huge": None}
THESIS_IN = {"smoke": False, "small": True, "default": True, "large": True, "huge": False}

SUMMARY_RE = re.compile(
    r"^\s+(?P<desc>.+?): (?P<dofs>\d+) DOFs, (?P<ls>\d+) load steps, (?P<sub>\d+) substeps, "
    r"(?P<it>\d+) iterations, (?P<stored>\d+) stored, (?P<fact>\d+) factorizations "
    r"\((?P<sym>\d+) symbolic\), (?P<solves>\d+) solves, (?P<chg>\d+) status changes, "
    r"(?P<secs>[0-9.]+) s$"
)
STEPPING_RE = re.compile(r"^\s+stepping: (?P<t_step>[0-9.]+) s, ")
SOLVER_RE = re.compile(
    r"^\s+linear solver: nnz\(K\) (?P<nnz_k>\d+), nnz\(L\) (?P<nnz_l>\d+), "
    r"factor (?P<factor_mb>[0-9.e+-]+) MB, analyze (?P<t_an>[0-9.]+) s, "
    r"factorize (?P<t_fa>[0-9.]+) s, solve (?P<t_so>[0-9.]+) s$"
)
TIME_BIN = "/usr/bin/time"


def parse_summary(text):
    """Analyses of a run summary: dicts of the counters, 'desc', 'secs' and, when the run
    printed them, the linear solver figures (nnz_k, nnz_l, factor_bytes, t_an, t_fa, t_so)."""
    out = []
    for line in text.splitlines():
        m = SUMMARY_RE.match(line)
        if m:
            d = {k: int(v) for k, v in m.groupdict().items() if k not in ("desc", "secs")}
            d["desc"] = m.group("desc")
            d["secs"] = float(m.group("secs"))
            out.append(d)
            continue
        m = STEPPING_RE.match(line)
        if m and out:
            out[-1]["t_step"] = float(m.group("t_step"))
            continue
        m = SOLVER_RE.match(line)
        if m and out:
            out[-1].update(nnz_k=int(m.group("nnz_k")), nnz_l=int(m.group("nnz_l")),
                           factor_bytes=float(m.group("factor_mb")) * 1e6,
                           t_an=float(m.group("t_an")), t_fa=float(m.group("t_fa")),
                           t_so=float(m.group("t_so")))
    return out


class BusyCore:
    """One `yes >/dev/null` process for the duration of a `with` block (a busy core)."""

    def __enter__(self):
        self.proc = subprocess.Popen(["yes"], stdout=subprocess.DEVNULL)
        time.sleep(0.2)
        return self

    def __exit__(self, *exc):
        self.proc.kill()
        self.proc.wait()


def timed(cmd, cwd, env=None):
    """Runs cmd; returns (wall s, cpu s, peak RSS kB, stdout). Raises on failure."""
    use_time = os.access(TIME_BIN, os.X_OK)
    stats_file = os.path.join(cwd, ".time_stats")
    full = [TIME_BIN, "-o", stats_file, "-f", "%M %U %S"] + cmd if use_time else cmd
    t0 = time.perf_counter()
    proc = subprocess.run(full, cwd=cwd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                          text=True)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError("%s failed (exit %d):\n%s%s" % (" ".join(cmd), proc.returncode,
                                                           proc.stdout[-3000:], proc.stderr[-3000:]))
    if use_time:
        with open(stats_file) as f:
            fields = f.read().split()
        rss, cpu = int(fields[-3]), float(fields[-2]) + float(fields[-1])
    else:
        # Re-run in a helper python whose only child is the command, so its RUSAGE_CHILDREN
        # maximum is this run's peak.
        helper = ("import resource,subprocess,sys;subprocess.run(sys.argv[1:],stdout=subprocess.DEVNULL,"
                  "stderr=subprocess.DEVNULL);r=resource.getrusage(resource.RUSAGE_CHILDREN);"
                  "print(r.ru_maxrss,r.ru_utime+r.ru_stime)")
        o = subprocess.run([sys.executable, "-c", helper] + cmd, cwd=cwd, env=env,
                           stdout=subprocess.PIPE, text=True)
        rss, cpu = int(o.stdout.split()[0]), float(o.stdout.split()[1])
    return wall, cpu, rss, proc.stdout


def impactfe_cmd(exe, deck, workdir, threads):
    cmd = [exe, "run", deck, "-o", workdir]
    if threads:
        cmd += ["--threads", str(threads)]
    return cmd


def median_or_nan(values):
    return statistics.median(values) if values else float("nan")


def run_case(exe, decks, repeat, threads=None, keep=None):
    """Runs a chain of decks `repeat` times; returns the figures of docs/benchmarks.md."""
    runs = []
    for r in range(repeat):
        workdir = tempfile.mkdtemp(prefix="impactfe_bench_")
        try:
            wall = cpu = 0.0
            rss = 0
            analyses = []
            for deck in decks:
                w, c, m, out = timed(impactfe_cmd(exe, deck, workdir, threads), workdir)
                wall += w
                cpu += c
                rss = max(rss, m)
                analyses += parse_summary(out)
            runs.append(dict(wall=wall, cpu=cpu, rss=rss, analyses=analyses))
        finally:
            if keep and r == repeat - 1:
                shutil.copytree(workdir, keep, dirs_exist_ok=True)
            shutil.rmtree(workdir, ignore_errors=True)
    analyses = runs[-1]["analyses"]
    # Time-integration analyses (expansion passes re-use the same steps).
    stepping = [i for i, a in enumerate(analyses)
                if "expansion" not in a["desc"] and "stress" not in a["desc"]]
    substeps = sum(analyses[i]["sub"] for i in stepping) or sum(a["sub"] for a in analyses)
    solver = [a for a in analyses if "nnz_l" in a]

    def per_run(fn):
        return median_or_nan([fn(run["analyses"]) for run in runs])

    def step_seconds(an):
        # The stepping loops' own wall time where the summary prints it (model set-up, the
        # initial state and the closing of the results excluded), else the analysis wall.
        s = sum(an[i].get("t_step", an[i]["secs"]) - an[i].get("t_an", 0.0) - an[i].get("t_fa", 0.0)
                for i in stepping)
        return s / substeps if substeps else float("nan")

    wall_med = statistics.median(r["wall"] for r in runs)
    res = {
        "wall_med": wall_med,
        "wall_min": min(r["wall"] for r in runs),
        "cpu_med": statistics.median(r["cpu"] for r in runs),
        "rss_mb": max(r["rss"] for r in runs) / 1024.0,
        "dofs": max((a["dofs"] for a in analyses), default=0),
        "substeps": substeps,
        "fact": sum(a["fact"] for a in analyses),
        "solves": sum(a["solves"] for a in analyses),
        "per_step_ms": 1e3 * wall_med / substeps if substeps else float("nan"),
        "analyses": "; ".join(a["desc"] for a in analyses),
        "has_solver": bool(solver),
        "repeats": repeat,
    }
    if solver:
        res.update(
            nnz_k=max(a["nnz_k"] for a in solver),
            nnz_l=max(a["nnz_l"] for a in solver),
            factor_bytes=max(a["factor_bytes"] for a in solver),
            t_analyze=per_run(lambda an: sum(a.get("t_an", 0.0) for a in an)),
            t_factorize=per_run(lambda an: sum(a.get("t_fa", 0.0) for a in an)),
            t_solve=per_run(lambda an: sum(a.get("t_so", 0.0) for a in an)),
            step_ms=1e3 * per_run(step_seconds),
        )
        solves = res["solves"]
        res["solve_ms"] = 1e3 * res["t_solve"] / solves if solves else float("nan")
    return res


def render_saved(path):
    """The tables of a run saved with --save (re-rendered with the current columns)."""
    with open(path) as f:
        saved = json.load(f)
    rows = [(name, r) for name, r in saved["cases"]]
    for _, r in rows:
        if r.get("has_solver") and "solve_ms" not in r:
            r["solve_ms"] = 1e3 * r["t_solve"] / r["solves"] if r["solves"] else float("nan")
        add_floor(r, saved["bandwidth"]["triad"])
    text = saved.get("header", "") + "\n" + table(rows)
    for name, cmp in saved["compare"]:
        text += compare_table("Block drop %s, side by side (medians)" % name, cmp)
    return text


def add_floor(res, bandwidth):
    """Bandwidth floor of a step: a solve reads L twice (forward and backward substitution)."""
    if res.get("has_solver") and bandwidth:
        res["floor_ms"] = 1e3 * 2.0 * res["factor_bytes"] / bandwidth
        res["step_floor_ratio"] = res["step_ms"] / res["floor_ms"] if res["floor_ms"] > 0 else float("nan")
        res["solve_floor_ratio"] = (res["solve_ms"] / res["floor_ms"] if res["floor_ms"] > 0
                                    else float("nan"))


def measure_bandwidth(bench_memory, repeat, min_time, length):
    """One-thread STREAM triad and read bandwidth (bytes/s, medians of `repeat` repetitions)."""
    cmd = [bench_memory, "--benchmark_filter=BM_Stream", "--benchmark_format=json",
           "--benchmark_repetitions=%d" % repeat, "--benchmark_min_time=%g" % min_time,
           "--length=%d" % length]
    proc = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if proc.returncode != 0:
        raise RuntimeError("%s failed:\n%s" % (" ".join(cmd), proc.stderr))
    per = {"triad": [], "read": []}
    for b in json.loads(proc.stdout)["benchmarks"]:
        if b.get("run_type", "iteration") != "iteration":
            continue
        key = "triad" if "Triad" in b["name"] else "read"
        per[key].append(float(b["bytes_per_second"]))
    return {k: statistics.median(v) for k, v in per.items() if v}


# --- the block drop and CalculiX ----------------------------------------------------------------

def blockdrop_name(nx, ny, nz, dt):
    return "blockdrop_%dx%dx%d" % (nx, ny, nz) + ("" if dt == 1e-5 else " (dt %g)" % dt)


def adapt_for_impactfe(path):
    """impactfe does not read NSEL yet (issue 9): replace the generator's selection of the ground
    nodes and D,ALL by the same constraint written as a node range, D,G0,ALL,0,,G1,1 (the ground
    nodes are numbered G0..G1 consecutively). Drop this once NSEL is implemented."""
    with open(path) as f:
        text = f.read()
    pattern = re.compile(r"^NSEL,S,NODE,,(\d+),(\d+)\nD,ALL,ALL,0\nNSEL,ALL\n", re.M)
    text, n = pattern.subn(lambda m: "D,%s,ALL,0,,%s,1\n" % (m.group(1), m.group(2)), text)
    if n != 1:
        raise RuntimeError("%s: the ground-node selection of gen_blockdrop.py was not found; "
                           "update adapt_for_impactfe" % path)
    with open(path, "w") as f:
        f.write(text)


def write_blockdrop(out, nx, ny, nz, dt):
    """Writes blockdrop_apdl.inp (impactfe) and blockdrop.inp (CalculiX) into out/; returns
    (APDL deck, CalculiX deck, corner node)."""
    os.makedirs(out, exist_ok=True)
    a = argparse.Namespace(nx=nx, ny=ny, nz=nz, dt=dt, tend=0.03, freq=10, alpha=0.0, etype="C3D8")
    m = gen_blockdrop.build(nx, ny, nz)
    apdl = os.path.join(out, "blockdrop_apdl.inp")
    gen_blockdrop.write_ccx(os.path.join(out, "blockdrop.inp"), m, a)
    gen_blockdrop.write_apdl(apdl, m, a)
    adapt_for_impactfe(apdl)
    return apdl, os.path.join(out, "blockdrop.inp"), m["corner"]


def impactfe_history(exe, h5, node):
    """(times, UZ) of a node from `impactfe post`."""
    proc = subprocess.run([exe, "post", h5, "--nsol", "%d,UZ" % node], stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, check=True)
    times, values = [], []
    for line in proc.stdout.splitlines()[1:]:
        t, v = line.split(",")
        times.append(float(t))
        values.append(float(v))
    return times, values


def ccx_history(dat, node):
    """(times, UZ) of a node from the *NODE PRINT blocks of a CalculiX .dat file."""
    times, values = [], []
    t = None
    head = re.compile(r"^\s*displacements \(vx,vy,vz\) for set \S+ and time\s+(\S+)")
    with open(dat) as f:
        for line in f:
            m = head.match(line)
            if m:
                t = float(m.group(1))
                continue
            fields = line.split()
            if t is not None and len(fields) == 4 and fields[0] == str(node):
                times.append(t)
                values.append(float(fields[3]))
                t = None
    return times, values


def history_difference(a, b):
    """Max |a - b| over the common times, relative to max |b|; and the number of common times.
    A run that stores t = 0 and one that does not still share every later point."""
    tb = {round(t, 12): v for t, v in zip(*b)}
    diffs = [abs(v - tb[round(t, 12)]) for t, v in zip(*a) if round(t, 12) in tb]
    peak = max((abs(v) for v in b[1]), default=0.0)
    if not diffs or peak == 0.0:
        return float("nan"), len(diffs)
    return max(diffs) / peak, len(diffs)


def compare_blockdrop(exe, nx, ny, nz, dt, repeat, ccx_repeat, use_ccx):
    """CalculiX and impactfe's thread modes on one block drop; returns a dict of rows."""
    tmp = tempfile.mkdtemp(prefix="impactfe_cmp_")
    try:
        apdl, ccx_deck, corner = write_blockdrop(tmp, nx, ny, nz, dt)
        rows = {}
        histories = {}
        modes = [("impactfe --threads 1", 1, False), ("impactfe default threads", None, False),
                 ("impactfe --threads 1, busy core", 1, True),
                 ("impactfe default threads, busy core", None, True)]
        for label, threads, busy in modes:
            walls, cpus = [], []
            for r in range(repeat):
                work = tempfile.mkdtemp(dir=tmp)
                cmd = impactfe_cmd(exe, apdl, work, threads)
                if busy:
                    with BusyCore():
                        w, c, _, _ = timed(cmd, work)
                else:
                    w, c, _, _ = timed(cmd, work)
                walls.append(w)
                cpus.append(c)
                if r == 0:
                    histories[label] = impactfe_history(exe, os.path.join(work, "blockdrop_apdl.h5"),
                                                        corner)
                shutil.rmtree(work, ignore_errors=True)
            rows[label] = dict(wall=statistics.median(walls), cpu=statistics.median(cpus),
                               n=repeat)
            print("  %-38s wall %.3f s  cpu %.3f s" % (label, rows[label]["wall"], rows[label]["cpu"]),
                  file=sys.stderr, flush=True)
        ref = histories["impactfe --threads 1"]
        for label in histories:
            rows[label]["diff"], rows[label]["points"] = history_difference(histories[label], ref)
        rows["impactfe --threads 1"]["min_uz"] = min(ref[1])
        if use_ccx:
            walls, cpus = [], []
            env = dict(os.environ)
            for r in range(ccx_repeat):
                work = tempfile.mkdtemp(dir=tmp)
                shutil.copy(ccx_deck, work)
                w, c, _, _ = timed(["ccx", "-i", "blockdrop"], work, env=env)
                walls.append(w)
                cpus.append(c)
                if r == 0:
                    ccx_hist = ccx_history(os.path.join(work, "blockdrop.dat"), corner)
                shutil.rmtree(work, ignore_errors=True)
            diff, points = history_difference(ref, ccx_hist)
            rows["CalculiX ccx"] = dict(wall=statistics.median(walls), cpu=statistics.median(cpus),
                                        n=ccx_repeat, diff=diff, points=points,
                                        min_uz=min(ccx_hist[1]))
            print("  %-38s wall %.3f s  cpu %.3f s  history diff %.2e" % (
                "CalculiX", rows["CalculiX ccx"]["wall"], rows["CalculiX ccx"]["cpu"], diff),
                file=sys.stderr, flush=True)
        return rows
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


# --- tables -------------------------------------------------------------------------------------

def fmt_num(value, spec):
    if value is None or value != value:  # None or NaN
        return "–"
    return spec % value


def table(rows):
    head = ("| case | DOFs | nnz(K) | nnz(L) | factor MB | substeps | fact. | solves | analyze s "
            "| factorize s | solve s | wall s (median) | wall s (min) | CPU s | per step ms "
            "| step ms | floor ms | step/floor | ms/solve | solve/floor | peak RSS MiB |\n"
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:"
            "|---:|---:|---:|---:|\n")
    body = ""
    for name, r in rows:
        body += "| %s |" % name + "|".join(" %s " % c for c in [
            "%d" % r["dofs"], fmt_num(r.get("nnz_k"), "%d"), fmt_num(r.get("nnz_l"), "%d"),
            fmt_num(r.get("factor_bytes", float("nan")) / 1e6, "%.3g"),
            "%d" % r["substeps"], "%d" % r["fact"], "%d" % r["solves"],
            fmt_num(r.get("t_analyze"), "%.4f"), fmt_num(r.get("t_factorize"), "%.4f"),
            fmt_num(r.get("t_solve"), "%.4f"), "%.3f" % r["wall_med"], "%.3f" % r["wall_min"],
            "%.3f" % r["cpu_med"], fmt_num(r["per_step_ms"], "%.3f"), fmt_num(r.get("step_ms"), "%.3f"),
            fmt_num(r.get("floor_ms"), "%.4f"), fmt_num(r.get("step_floor_ratio"), "%.3g"),
            fmt_num(r.get("solve_ms"), "%.4f"), fmt_num(r.get("solve_floor_ratio"), "%.3g"),
            "%.1f" % r["rss_mb"]]) + "|\n"
    return head + body


def compare_table(name, rows):
    ref = rows.get("CalculiX ccx")
    head = ("\n%s\n\n| program | runs | wall s (median) | CPU s (median) | CalculiX wall / this "
            "| CalculiX CPU / this | history diff vs impactfe --threads 1 | min corner UZ |\n"
            "|---|---:|---:|---:|---:|---:|---:|---:|\n" % name)
    body = ""
    for label, r in rows.items():
        body += "| %s | %d | %.3f | %.3f | %s | %s | %s | %s |\n" % (
            label, r["n"], r["wall"], r["cpu"],
            fmt_num(ref["wall"] / r["wall"] if ref else None, "%.1f×"),
            fmt_num(ref["cpu"] / r["cpu"] if ref and r["cpu"] > 0 else None, "%.1f×"),
            "%.2e (%d points)" % (r["diff"], r["points"]) if "diff" in r else "–",
            fmt_num(r.get("min_uz"), "%.6e"))
    return head + body


def machine_line(args, bandwidth, load_before, load_after):
    git = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                         stderr=subprocess.DEVNULL, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", ROOT, "status", "--porcelain", "--untracked-files=no"],
                           stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True).stdout.strip()
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    mem = ""
    try:
        with open("/proc/meminfo") as f:
            mem = "%.1f GiB RAM" % (int(f.readline().split()[1]) / 2**20)
    except OSError:
        pass
    return ("impactfe %s%s, %s, %s, %d CPUs, %s, sizes %s, %d repeats, threads %s, %s; "
            "bandwidth (1 thread) triad %.2f GB/s, read %.2f GB/s; load average %.2f before, "
            "%.2f after\n" % (
                git or "?", " (modified)" if dirty else "", platform.node(), cpu, os.cpu_count() or 0,
                mem, args.sizes, args.repeat, args.threads or "default",
                datetime.datetime.now().isoformat(timespec="seconds"),
                bandwidth.get("triad", 0) / 1e9, bandwidth.get("read", 0) / 1e9, load_before,
                load_after))


def check_results(rows, bandwidth, compare):
    """--check: every figure the suite promises is present and sane (the CI smoke test)."""
    problems = []
    if not bandwidth.get("triad", 0) > 0:
        problems.append("no memory bandwidth measured")
    for name, r in rows:
        if r["dofs"] <= 0 or r["substeps"] <= 0 or not r["wall_med"] > 0 or not r["rss_mb"] > 0:
            problems.append("%s: missing DOFs, substeps, wall time or peak memory" % name)
        direct = "link_bar" not in name  # reduced runs do not report solver figures yet
        if direct:
            if not r.get("has_solver"):
                problems.append("%s: the run summary has no linear solver figures" % name)
            elif not (r["nnz_l"] >= r["nnz_k"] > 0 and r["factor_bytes"] >= 8 * r["nnz_l"]
                      and r["t_factorize"] > 0 and r["t_solve"] > 0 and r["fact"] > 0
                      and r.get("floor_ms", 0) > 0):
                problems.append("%s: implausible solver figures %s" % (name, r))
    for name, cmp in compare:
        for label, r in cmp.items():
            if not r.get("diff", 1.0) <= 0.005:
                problems.append("%s / %s: monitored history differs by %s of its peak"
                                % (name, label, r.get("diff")))
    return problems


def loadavg():
    try:
        return os.getloadavg()[0]
    except OSError:
        return float("nan")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "impactfe"))
    ap.add_argument("--bench-memory", default=os.path.join(ROOT, "build", "bench", "bench_memory"),
                    help="the bandwidth benchmark (bench/bench_memory.cpp)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--sizes", choices=sorted(BLOCKDROP_SIZES), default="default",
                    help="model set: smoke (CI), small, default, large (+ 10^5 DOFs), huge (10^6)")
    ap.add_argument("--threads", type=int, default=1,
                    help="impactfe --threads for the main table (0: impactfe's default)")
    ap.add_argument("--no-thesis", action="store_true", help="skip the thesis decks")
    ap.add_argument("--no-scaled", action="store_true", help="skip generate_models.py's models")
    ap.add_argument("--no-blockdrop", action="store_true", help="skip the block drops")
    ap.add_argument("--only", default="", help="run only cases whose name contains this text")
    ap.add_argument("--compare", action="store_true",
                    help="CalculiX and thread modes on the block drops (needs ccx for CalculiX)")
    ap.add_argument("--compare-max-dofs", type=int, default=2000)
    ap.add_argument("--ccx-repeat", type=int, default=3)
    ap.add_argument("--no-ccx", action="store_true", help="--compare without CalculiX")
    ap.add_argument("--bandwidth-repeat", type=int, default=5)
    ap.add_argument("--bandwidth-min-time", type=float, default=0.5)
    ap.add_argument("--bandwidth-length", type=int, default=1 << 24,
                    help="doubles per array of the bandwidth kernels (default 2^24: 128 MiB)")
    ap.add_argument("--check", action="store_true",
                    help="fail unless every figure is present and plausible (CI smoke test)")
    ap.add_argument("--save", action="store_true", help="write bench/results/<date>-<sizes>.md/.json")
    ap.add_argument("--render", metavar="JSON", help="print the tables of a saved run and exit")
    args = ap.parse_args()
    if args.render:
        print(render_saved(args.render))
        return
    exe = os.path.abspath(args.exe)
    if not os.access(exe, os.X_OK):
        sys.exit("impactfe executable not found: %s (build it first)" % exe)
    bench_memory = os.path.abspath(args.bench_memory)
    if not os.access(bench_memory, os.X_OK):
        sys.exit("bench_memory not found: %s (cmake --build build --target bench_memory)" % bench_memory)

    load_before = loadavg()
    print("measuring memory bandwidth ...", file=sys.stderr, flush=True)
    bw_runs = [measure_bandwidth(bench_memory, args.bandwidth_repeat, args.bandwidth_min_time,
                                   args.bandwidth_length)]

    cases = []
    if THESIS_IN[args.sizes] and not args.no_thesis:
        cases += [(n, [os.path.join(THESIS, d) for d in ds]) for n, ds in THESIS_CASES]
    model_dir = tempfile.mkdtemp(prefix="impactfe_models_")
    if SCALED_SET[args.sizes] and not args.no_scaled:
        cases += [(n, [p]) for n, p in generate_models.generate(model_dir, SCALED_SET[args.sizes]).items()]
    blockdrops = [] if args.no_blockdrop else BLOCKDROP_SIZES[args.sizes]
    for nx, ny, nz, dt in blockdrops:
        name = blockdrop_name(nx, ny, nz, dt)
        apdl, _, _ = write_blockdrop(os.path.join(model_dir, name.split()[0]), nx, ny, nz, dt)
        cases.append((name, [apdl]))
    cases = [c for c in cases if args.only in c[0]]

    rows, compare = [], []
    try:
        for name, decks in cases:
            print("running %-28s x%d ..." % (name, args.repeat), file=sys.stderr, flush=True)
            r = run_case(exe, decks, args.repeat, threads=args.threads)
            rows.append((name, r))
            print("  median %.3f s  (%s)" % (r["wall_med"], r["analyses"]), file=sys.stderr, flush=True)
        if args.compare:
            use_ccx = shutil.which("ccx") is not None and not args.no_ccx
            if not use_ccx and not args.no_ccx:
                print("ccx not found (apt-get install calculix-ccx): impactfe thread modes only",
                      file=sys.stderr)
            for nx, ny, nz, dt in blockdrops:
                name = blockdrop_name(nx, ny, nz, dt)
                if args.only not in name or 3 * (nx + 1) * (ny + 1) * (nz + 1) > args.compare_max_dofs:
                    continue
                print("comparing %s ..." % name, file=sys.stderr, flush=True)
                compare.append((name, compare_blockdrop(exe, nx, ny, nz, dt, args.repeat,
                                                        args.ccx_repeat, use_ccx)))
    finally:
        shutil.rmtree(model_dir, ignore_errors=True)

    bw_runs.append(measure_bandwidth(bench_memory, args.bandwidth_repeat, args.bandwidth_min_time,
                                   args.bandwidth_length))
    bandwidth = {k: max(b[k] for b in bw_runs) for k in ("triad", "read")}
    for _, r in rows:
        add_floor(r, bandwidth["triad"])

    header = machine_line(args, bandwidth, load_before, loadavg())
    text = header + "\n" + table(rows)
    for name, cmp in compare:
        text += compare_table("Block drop %s, side by side (medians; impactfe %d runs each)"
                              % (name, args.repeat), cmp)
    print(text)
    if args.save:
        os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
        stem = os.path.join(HERE, "results", "%s-%s" % (datetime.date.today().isoformat(), args.sizes))
        with open(stem + ".md", "w") as f:
            f.write("# impactfe benchmark run\n\n" + text)
        with open(stem + ".json", "w") as f:
            json.dump({"header": header, "bandwidth": bandwidth, "bandwidth_runs": bw_runs,
                       "cases": rows, "compare": compare}, f, indent=1)
        print("written %s.md, .json" % stem, file=sys.stderr)
    if args.check:
        problems = check_results(rows, bandwidth, compare)
        for p in problems:
            print("CHECK FAILED: " + p, file=sys.stderr)
        if problems:
            sys.exit(1)
        print("check: all figures present (%d cases)" % len(rows), file=sys.stderr)


if __name__ == "__main__":
    main()

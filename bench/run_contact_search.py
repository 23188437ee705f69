#!/usr/bin/env python3
"""Cost of the contact search against the cost of a step with contact (issue 16), 10^3..10^5
contact nodes. Stdlib only; docs/benchmarks.md ("Contact search") explains the columns.

    python3 bench/run_contact_search.py --exe build/impactfe \
        --bench build/bench/bench_contact_search [--sizes 1e3,1e4,1e5] [--extra-steps 4]
    (--sizes smoke --extra-steps 1 --check: the CI smoke test, 64 contact nodes)

Per size (a block NX x NY x NZ on a rigid meshed floor, bench/gen_contact_block.py, with
(NX+1)(NY+1) contact nodes):
  * bench_contact_search: CPU time of one search sweep (every contact node queries the floor's
    bucket grid once, as CONTA175 does before each status update) and of building the grid;
  * impactfe run of the deck with 1 step and with 1 + K steps: CPU time (user + sys of the
    process, getrusage); per step = the difference / K (the steps after the first, all contacts
    closed, no status change: assembly, contact update, residual and a solve with the factor of
    the first step); the first step's factorization from the run summary;
  * search share = (equilibrium iterations per step x sweep) / per step.
CPU rather than wall time: the machine is shared (the load average is printed).
"""
import argparse
import os
import re
import resource
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import gen_contact_block  # noqa: E402

SIZES = {"smoke": (7, 7, 1), "1e3": (31, 31, 2), "1e4": (99, 99, 1), "1e5": (316, 316, 1)}
MESH_ARG = {"smoke": 8, "1e3": 32, "1e4": 100, "1e5": 317}  # bench_contact_search's m for the same size


def cpu_run(args, cwd):
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(args, cwd=cwd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if p.returncode != 0:
        sys.exit(f"{' '.join(args)} failed ({p.returncode}):\n{p.stdout[-2000:]}{p.stderr[-2000:]}")
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    return cpu, p.stdout + p.stderr, after.ru_maxrss


def summary_number(text, pattern):
    m = re.search(pattern, text)
    return float(m.group(1)) if m else float("nan")


def search_times(bench, m):
    """(sweep CPU s, build CPU s, per-query CPU s) from bench_contact_search for floor size m."""
    out = subprocess.run([bench, f"--benchmark_filter=(BM_TargetBuild|BM_SearchMeshedFloor)/{m}$",
                          "--benchmark_min_time=0.2", "--benchmark_format=console",
                          "--benchmark_time_unit=ms"], capture_output=True, text=True).stdout

    def cpu_ms(name):
        m_ = re.search(rf"{name}/{m}\s+\S+ ms\s+(\S+) ms", out)
        return float(m_.group(1)) / 1e3 if m_ else float("nan")

    sweep, build = cpu_ms("BM_SearchMeshedFloor"), cpu_ms("BM_TargetBuild")
    return sweep, build


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--exe", default=os.path.join(HERE, "..", "build", "impactfe"))
    ap.add_argument("--bench", default=os.path.join(HERE, "..", "build", "bench",
                                                    "bench_contact_search"))
    ap.add_argument("--sizes", default="1e3,1e4")
    ap.add_argument("--extra-steps", type=int, default=4)
    ap.add_argument("--threads", type=int, default=1,
                    help="impactfe --threads (default 1: OpenMP threads spinning on a loaded "
                         "machine would count as CPU time)")
    ap.add_argument("--workdir", default=None)
    ap.add_argument("--one-facet", action="store_true",
                    help="runs on a one-quad floor (the element setup checks the meshed floor's "
                         "facets once per contact element: quadratic, see docs/benchmarks.md)")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 unless every figure is there and plausible (the CI smoke test)")
    a = ap.parse_args()
    a.exe, a.bench = os.path.abspath(a.exe), os.path.abspath(a.bench)
    work = a.workdir or tempfile.mkdtemp(prefix="contact_search_")
    print(f"load average before: {os.getloadavg()[0]:.1f}")
    rows = []
    for size in a.sizes.split(","):
        nx, ny, nz = SIZES[size]
        sweep, build = search_times(a.bench, MESH_ARG[size])
        cpus, outs = [], []
        for steps in (1, 1 + a.extra_steps):
            d = os.path.join(work, f"{size}_{steps}")
            deck = gen_contact_block.write(nx, ny, nz, d, steps, 1e-5, a.one_facet)
            cpu, text, rss = cpu_run(
                [a.exe, "run", deck, "-o", d, "--threads", str(a.threads)], d)
            cpus.append(cpu)
            outs.append(text)
        text = outs[1]
        dofs = summary_number(text, r"\(Newmark\): (\d+) DOFs")
        iters = summary_number(text, r"substeps, (\d+) iterations")
        substeps = summary_number(text, r"load steps, (\d+) substeps")
        factorize = summary_number(text, r"factorize ([\d.e+-]+) s")
        status = summary_number(text, r"(\d+) status changes")
        per_step = (cpus[1] - cpus[0]) / a.extra_steps
        search = iters / substeps * sweep
        if a.check and not (dofs > 0 and substeps == 1 + a.extra_steps and sweep > 0
                            and build > 0 and status == 0):
            sys.exit(f"{size}: implausible figures: DOFs {dofs}, substeps {substeps}, "
                     f"sweep {sweep}, build {build}, status changes {status}")
        rows.append((size, (nx + 1) * (ny + 1), int(dofs), sweep, build, cpus[0], cpus[1],
                     per_step, factorize, search / per_step, int(status), rss / 1024))
    print(f"load average after: {os.getloadavg()[0]:.1f}")
    print("| contact nodes | DOFs | search sweep ms | grid build ms | run CPU s (1 step) | "
          f"run CPU s ({1 + a.extra_steps} steps) | step CPU ms | factorize s (wall) | "
          "search / step | status changes | peak RSS MiB |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r[1]} | {r[2]} | {r[3] * 1e3:.3g} | {r[4] * 1e3:.3g} | {r[5]:.2f} | "
              f"{r[6]:.2f} | {r[7] * 1e3:.3g} | {r[8]:.3g} | {100 * r[9]:.2g} % | {r[10]} | "
              f"{r[11]:.0f} |")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""MUMPS (`--solver mumps` under mpirun) against CHOLMOD (the default, one process): analyse,
factorise and solve wall times and peak memory per rank, on static SOLID185 blocks of growing
size (docs/scaling.md). Prints a Markdown table.

The times are the run summary's solver counters (rank 0's wall clock for MUMPS, which is the
time of the collective call); the memory is each process's peak resident set (/usr/bin/time),
which includes the model, the assembly and, for MUMPS, the MPI buffers.

usage: mumps_vs_cholmod.py IMPACTFE [--sizes 8,12,16] [--ranks 1,2,4] [--out DIR]
Size n is a block of n x n/4 x n/4 bricks: 16 -> 1200 DOFs, 32 -> 7776, 48 -> 24336 (keep it small
on a shared machine; docs/scaling.md has the measured table)."""
import argparse
import os
import re
import shutil
import subprocess

MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_rmaps_base_oversubscribe": "1",
    "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
    "OMPI_MCA_mpi_yield_when_idle": "1",
    "OMP_NUM_THREADS": "1",
}
SOLVER_LINE = re.compile(r"linear solver: nnz\(K\) (\d+), nnz\(L\) (\d+), factor ([\d.e+-]+) MB, "
                         r"analyze ([\d.e+-]+) s, factorize ([\d.e+-]+) s, solve ([\d.e+-]+) s")
RSS = re.compile(r"impactfe-maxrss (\d+)")


def block_deck(path, n):
    """A clamped 4 x 1 x 1 SOLID185 cantilever meshed with n x n/4 x n/4 bricks of edge 4/n."""
    with open(path, "w") as f:
        f.write(f"""! bench/mumps_vs_cholmod.py: SOLID185 cantilever 4 x 1 x 1, {n} x {n // 4} x {n // 4} bricks
/PREP7
ET,1,SOLID185
MP,EX,1,30E6
MP,PRXY,1,0.3
MP,DENS,1,7.3E-4
BLOCK,0,4,0,1,0,1
ESIZE,{4.0 / n}
VMESH,ALL
NSEL,S,LOC,X,0
D,ALL,ALL
NSEL,S,LOC,X,4
F,ALL,FZ,-10
ALLSEL
FINISH
/SOLU
ANTYPE,STATIC
SOLVE
FINISH
""")


def run(command, out):
    shutil.rmtree(out, ignore_errors=True)
    os.makedirs(out)
    p = subprocess.run(command, capture_output=True, text=True, env=dict(os.environ, **MPI_ENV))
    if p.returncode != 0:
        raise SystemExit(f"{' '.join(command)} failed:\n{p.stdout}\n{p.stderr}")
    m = SOLVER_LINE.search(p.stdout)
    dofs = re.search(r"(\d+) DOFs", p.stdout)
    rss = [int(x) / 1024.0 for x in RSS.findall(p.stderr)]
    return (int(dofs.group(1)), int(m.group(2)), float(m.group(4)), float(m.group(5)),
            float(m.group(6)), max(rss), sum(rss))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("impactfe")
    ap.add_argument("--sizes", default="8,16")
    ap.add_argument("--ranks", default="1,2,4")
    ap.add_argument("--out", default="mumps_bench_out")
    a = ap.parse_args()
    binary = os.path.abspath(a.impactfe)
    timer = ["/usr/bin/time", "-f", "impactfe-maxrss %M"]
    print("| DOFs | solver | ranks | nnz(L) | analyse s | factorise s | solve s | "
          "peak RSS per rank MB (max) | sum over ranks MB |")
    print("|---:|---|---:|---:|---:|---:|---:|---:|---:|")
    for n in [int(s) for s in a.sizes.split(",")]:
        deck = os.path.abspath(os.path.join(a.out, f"block{n}.inp"))
        os.makedirs(a.out, exist_ok=True)
        block_deck(deck, n)
        rows = [("CHOLMOD", 1, run(timer + [binary, "run", deck, "-o", os.path.join(a.out, "c"),
                                            "--threads", "1"], os.path.join(a.out, "c")))]
        for r in [int(s) for s in a.ranks.split(",")]:
            out = os.path.join(a.out, f"m{r}")
            rows.append(("MUMPS", r, run(["mpirun", "-n", str(r)] + timer +
                                         [binary, "run", deck, "-o", out, "--solver", "mumps"],
                                         out)))
        for name, r, (dofs, lnz, ta, tf, ts, rss, total) in rows:
            print(f"| {dofs} | {name} | {r} | {lnz} | {ta:.4f} | {tf:.4f} | {ts:.4f} | "
                  f"{rss:.1f} | {total:.1f} |")


if __name__ == "__main__":
    main()

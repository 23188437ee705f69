#!/usr/bin/python3
"""Rank 0 reads the deck and every file it names, the other ranks receive them by broadcast
(docs/scaling.md): a deck on a disk only rank 0 sees runs. mpirun starts rank 0 in directory A,
which holds the decks, and rank 1 in an empty directory B (Open MPI MPMD syntax, one --wdir per
rank); every path on the command line is relative, so rank 1 can open none of them itself:
- a static deck whose model comes from a file read with /INPUT,
- the helmet's generation pass, then its use pass, which reads the superelement file that the
  generation pass left in the (relative) output directory,
each result equal to a one-process CHOLMOD run to 1e-10 relative (the helmet's use pass to 1e-6:
its gap impacts amplify the superelement's round-off, docs/scaling.md), and nothing written in B.
Exit 77 (CTest: skipped) when mpirun or the MUMPS module is missing.

usage: rank0_files.py IMPACTFE STATIC_DECK HELMET_SEGEN HELMET_USE OUTDIR"""
import os
import shutil
import subprocess
import sys

import numpy as np

from compare_mumps import MPI_ENV, SKIP, datasets


def run(command, cwd):
    env = dict(os.environ, **MPI_ENV)
    p = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300, cwd=cwd)
    if p.returncode != 0:
        sys.exit(f"FAIL {' '.join(command)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p.stdout


def worst_difference(result, reference):
    worst = 0.0
    for path, y in reference.items():
        x = result.get(path)
        if x is None or x.shape != y.shape:
            return float("inf")
        finite = np.isfinite(y)
        if not np.array_equal(finite, np.isfinite(x)):
            return float("inf")
        if not finite.any() or path.endswith("/A"):
            continue  # accelerations: see compare_mumps.py
        peak = np.max(np.abs(y[finite]))
        diff = np.max(np.abs(x[finite] - y[finite]))
        worst = max(worst, diff / peak if peak > 0 else diff)
    return worst


def main():
    binary, static_deck, segen, use, out = [os.path.abspath(a) for a in sys.argv[1:6]]
    mpirun = shutil.which("mpirun")
    module = os.path.join(os.path.dirname(binary), "libimpactfe_mumps.so")
    if not mpirun or not os.path.exists(module):
        print(f"SKIP: {'mpirun' if not mpirun else module} not found")
        sys.exit(SKIP)
    root = os.path.join(out, "rank0_files")
    shutil.rmtree(root, ignore_errors=True)
    a, b = os.path.join(root, "A"), os.path.join(root, "B")
    os.makedirs(a)
    os.makedirs(b)
    # The static deck split: the model in a file of its own, read with /INPUT.
    lines = open(static_deck).read().splitlines()
    cut = lines.index("/SOLU")
    with open(os.path.join(a, "block_model.inp"), "w") as f:
        f.write("\n".join(lines[:cut]) + "\n")
    with open(os.path.join(a, "block.inp"), "w") as f:
        f.write("/INPUT,block_model,inp\n" + "\n".join(lines[cut:]) + "\n")
    shutil.copy(segen, a)
    shutil.copy(use, a)
    segen, use = os.path.basename(segen), os.path.basename(use)

    def mpi(deck):
        args = [binary, "run", deck, "-o", "mumps", "--solver", "mumps"]
        return [mpirun, "-n", "1", "--wdir", a] + args + [":", "-n", "1", "--wdir", b] + args

    failures = []
    for decks, tolerance in ((["block.inp"], 1e-10), ([segen, use], 1e-6)):
        for deck in decks:
            run([binary, "run", deck, "-o", "cholmod"], a)
            stdout = run(mpi(deck), a)
            if "MUMPS on 2 MPI rank(s)" not in stdout:
                failures.append(f"{deck}: the summary does not name MUMPS on 2 ranks")
        stem = os.path.splitext(decks[-1])[0]
        files = [stem + ".h5"] + (["helmet_segen.sub.h5"] if len(decks) > 1 else [])
        for name, limit in zip(files, (tolerance, 1e-10)):
            worst = worst_difference(datasets(os.path.join(a, "mumps", name)),
                                     datasets(os.path.join(a, "cholmod", name)))
            print(f"{name}: largest relative difference to CHOLMOD {worst:.2e} (limit {limit:g})")
            if not worst <= limit:
                failures.append(f"{name}: {worst:.2e} relative to CHOLMOD (limit {limit:g})")
    if os.listdir(b):
        failures.append(f"rank 1 wrote into its own directory: {os.listdir(b)}")
    if failures:
        sys.exit("FAIL: " + "; ".join(failures))
    print("OK")


if __name__ == "__main__":
    main()

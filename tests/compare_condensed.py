#!/usr/bin/python3
"""Runs a transient deck twice, with the condensed linear part (the default) and with
--no-condense, and checks that every stored result agrees to 1e-9 relative (to the peak of each
result array) — accelerations to 1e-7: a_{n+1} = (u_{n+1} − ũ)/(β Δt²) amplifies the round-off of
u by 1/(β Δt²) (4·10¹⁰ at Δt = 1e-5), whichever path solved it. With --expect-condensed the
default run must report that it condensed.

usage: compare_condensed.py IMPACTFE DECK OUTDIR [--expect-condensed]"""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

TOLERANCE = 1e-9
ACCELERATION_TOLERANCE = 1e-7


def run(binary, deck, outdir, extra):
    os.makedirs(outdir, exist_ok=True)
    p = subprocess.run([binary, "run", deck, "-o", outdir] + extra, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"FAIL {deck} {' '.join(extra)}: exit {p.returncode}\n{p.stderr}")
    return p.stdout


def main():
    binary, deck, out = sys.argv[1:4]
    expect = "--expect-condensed" in sys.argv
    name = os.path.splitext(os.path.basename(deck))[0]
    root = os.path.join(out, name)
    shutil.rmtree(root, ignore_errors=True)
    condensed = run(binary, os.path.abspath(deck), os.path.join(root, "condensed"), [])
    full = run(binary, os.path.abspath(deck), os.path.join(root, "full"), ["--no-condense"])
    used = "condensed transient:" in condensed
    print(f"{name}: condensed path {'used' if used else 'not used'}")
    if expect and not used:
        sys.exit(f"FAIL {name}: the condensed path was not used\n{condensed}")
    failures = []
    with h5py.File(os.path.join(root, "condensed", name + ".h5"), "r") as a, \
         h5py.File(os.path.join(root, "full", name + ".h5"), "r") as b:
        def visit(path, obj):
            if not isinstance(obj, h5py.Dataset) or obj.dtype.kind != "f":
                return
            x, y = obj[()], b[path][()]
            if x.shape != y.shape:
                failures.append(f"{path}: shape {x.shape} vs {y.shape}")
                return
            both = np.isfinite(x) & np.isfinite(y)
            if not np.array_equal(np.isfinite(x), np.isfinite(y)):
                failures.append(f"{path}: NaN pattern differs")
            if not both.any():
                return
            peak = np.max(np.abs(y[both]))
            diff = np.max(np.abs(x[both] - y[both]))
            rel = diff / peak if peak > 0 else diff
            print(f"  {path}: max |condensed - full| = {diff:.3e} ({rel:.1e} of peak {peak:.3e})")
            limit = ACCELERATION_TOLERANCE if path.endswith("/A") else TOLERANCE
            if rel > limit:
                failures.append(f"{path}: {rel:.2e} relative")
        a.visititems(visit)
    if failures:
        sys.exit("FAIL " + name + ": " + "; ".join(failures))
    # A passing case's files go (CI disk); IMPACTFE_KEEP_TEST_OUTPUT=1 keeps them.
    if not os.environ.get("IMPACTFE_KEEP_TEST_OUTPUT"):
        shutil.rmtree(root, ignore_errors=True)
    print("OK")


main()

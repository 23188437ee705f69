#!/usr/bin/python3
"""Runs two impactfe binaries on every regression and verification deck and compares their
results files bitwise: a restructuring of the solver must not change one bit of what it writes.

usage: compare-results.py BEFORE AFTER [--out DIR] [--reuse-before] [--timeout S] [DECK ...]

Decks (default): tests/decks/**/*.inp, tests/verification/*.inp, examples/*.inp. The decks of
one directory run in name order in one output directory per binary (a deck may read what an
earlier one wrote: helmet_segen before helmet_use, crash1 before crash1_post26). For each deck
the exit status must agree, the same .h5 files must be written, and in each file every dataset
must have the same path, type, shape and bytes (NaN patterns included) and every attribute the
same value, except attributes that measure the run itself (wall time, phase seconds, dates,
program version and commit). --reuse-before keeps BEFORE's outputs of an earlier call (the
baseline does not change). Exit status 0 when everything agrees."""
import argparse
import os
import pathlib
import shutil
import subprocess
import sys

import h5py
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
# Attributes that describe the run rather than its results (times, dates, program identity).
VOLATILE = ("seconds", "wall", "date", "time_created", "created", "version", "commit", "host")


def decks_of_repository():
    found = sorted((ROOT / "tests" / "decks").rglob("*.inp"))
    found += sorted((ROOT / "tests" / "verification").glob("*.inp"))
    found += sorted((ROOT / "examples").glob("*.inp"))
    return found


def relative(directory):
    """A deck directory as a path inside the output directory."""
    if directory.is_relative_to(ROOT):
        return directory.relative_to(ROOT)
    return pathlib.Path("other") / directory.name


def volatile(name):
    lower = name.lower()
    return any(v in lower for v in VOLATILE)


def h5_stamps(out):
    return {p.name: p.stat().st_mtime_ns for p in out.glob("*.h5")}


def run(binary, deck, out, timeout):
    """Runs `deck` with its outputs in `out`; returns the exit status and the .h5 files the run
    wrote (new or changed), both also kept beside the outputs for --reuse-before."""
    out.mkdir(parents=True, exist_ok=True)
    stamps = h5_stamps(out)
    try:
        p = subprocess.run([binary, "run", str(deck), "-o", str(out)], capture_output=True,
                           text=True, timeout=timeout, cwd=out)
        status = str(p.returncode)
    except subprocess.TimeoutExpired:
        status = "timeout"
    written = sorted(n for n, t in h5_stamps(out).items() if stamps.get(n) != t)
    (out / (deck.stem + ".status")).write_text("\n".join([status] + written) + "\n")
    return status, written


def same_values(x, y):
    """Bitwise equality of two arrays; variable-length strings and objects by value (their
    bytes in memory are pointers)."""
    x, y = np.asarray(x), np.asarray(y)
    if x.dtype != y.dtype or x.shape != y.shape:
        return False
    if x.dtype.hasobject:
        return x.tolist() == y.tolist()
    return x.tobytes() == y.tobytes()


def compare_attributes(path, a, b, problems):
    keys = {k for k in list(a.attrs) + list(b.attrs) if not volatile(k)}
    for k in sorted(keys):
        if k not in a.attrs or k not in b.attrs:
            problems.append(f"{path}@{k}: only in {'before' if k in a.attrs else 'after'}")
            continue
        if not same_values(a.attrs[k], b.attrs[k]):
            problems.append(f"{path}@{k}: {a.attrs[k]!r} vs {b.attrs[k]!r}")


def compare_files(before, after):
    """Problems found between two .h5 files (empty: bitwise equal); the number of datasets."""
    problems = []
    count = 0
    with h5py.File(before, "r") as fa, h5py.File(after, "r") as fb:
        names_a, names_b = [], []
        fa.visit(names_a.append)
        fb.visit(names_b.append)
        for name in sorted(set(names_a) ^ set(names_b)):
            problems.append(f"{name}: only in {'before' if name in names_a else 'after'}")
        compare_attributes("/", fa, fb, problems)
        for name in sorted(set(names_a) & set(names_b)):
            a, b = fa[name], fb[name]
            compare_attributes(name, a, b, problems)
            if not isinstance(a, h5py.Dataset):
                continue
            count += 1
            if volatile(name.rsplit("/", 1)[-1]):
                continue
            x, y = a[()], b[()]
            if a.dtype != b.dtype or a.shape != b.shape:
                problems.append(f"{name}: {a.dtype}{a.shape} vs {b.dtype}{b.shape}")
            elif not same_values(x, y):
                problems.append(f"{name}: values differ")
    return problems, count


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("decks", nargs="*")
    parser.add_argument("--out", default=str(ROOT / "build" / "compare-results"))
    parser.add_argument("--reuse-before", action="store_true")
    parser.add_argument("--timeout", type=float, default=900)
    args = parser.parse_intermixed_args()
    decks = [pathlib.Path(d).resolve() for d in args.decks] or decks_of_repository()
    out = pathlib.Path(args.out)
    # Fresh output directories (the baseline's too unless it is reused).
    sides = ["after"] if args.reuse_before else ["before", "after"]
    for side in sides:
        for directory in {d.parent for d in decks}:
            shutil.rmtree(out / side / relative(directory), ignore_errors=True)
    failures, n_files, n_datasets = [], 0, 0
    for deck in decks:
        directory = relative(deck.parent)
        results, written = {}, {}
        for side, binary in (("before", args.before), ("after", args.after)):
            where = out / side / directory
            status_file = where / (deck.stem + ".status")
            if side == "before" and args.reuse_before and status_file.exists():
                lines = status_file.read_text().split()
                results[side], written[side] = lines[0], lines[1:]
                continue
            results[side], written[side] = run(os.path.abspath(binary), deck, where,
                                               args.timeout)
        problems = []
        if results["before"] != results["after"]:
            problems.append(f"exit status {results['before']} vs {results['after']}")
        files_before, files_after = set(written["before"]), set(written["after"])
        for name in sorted(files_before ^ files_after):
            problems.append(f"{name}: written only {'before' if name in files_before else 'after'}")
        for name in sorted(files_before & files_after):
            found, count = compare_files(out / "before" / directory / name,
                                         out / "after" / directory / name)
            problems += [f"{name}: {p}" for p in found]
            n_files += 1
            n_datasets += count
        label = f"{directory}/{deck.name}"
        print(f"{'DIFF' if problems else 'same'} {label} (exit {results['after']}, "
              f"{len(files_after)} h5)", flush=True)
        for p in problems[:20]:
            print(f"    {p}")
        if problems:
            failures.append(label)
    print(f"{len(decks)} decks, {n_files} results files, {n_datasets} datasets compared; "
          f"{len(failures)} deck(s) differ")
    for f in failures:
        print(f"  differs: {f}")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

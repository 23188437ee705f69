#!/usr/bin/python3
"""Runs a deck with the default CHOLMOD (one process) and with `--solver mumps` under mpirun on
1, 2 and 4 ranks (docs/scaling.md), each MUMPS run twice, and checks that
- every stored floating-point result equals CHOLMOD's to 1e-10 relative to the peak of its array
  (accelerations to ACCELERATION_TOLERANCE: a_{n+1} = (u_{n+1} - u~)/(beta dt^2) amplifies the
  round-off of u by 1/(beta dt^2), whichever solver produced it),
- the two runs on the same rank count are bitwise equal (one run with --mumps-no-refine, which
  gives that up),
- the run summary names MUMPS and the rank count, and only rank 0 wrote files.
Exit 77 (CTest: skipped) when mpirun or the MUMPS module is missing.

With --pre DECK0, DECK0 (a superelement generation pass) runs first in the same output directory,
with the same solver and rank count, and DECK (the use pass) reads what it wrote; the
superelement files (*.sub.h5) are then compared to 1e-10 as well. --tolerance replaces 1e-10 for
DECK's results (a gap impact amplifies round-off: docs/scaling.md).

usage: compare_mumps.py IMPACTFE DECK OUTDIR [--ranks 1,2,4] [--pre DECK0] [--tolerance T]
                        [-- extra impactfe arguments]
The environment variable IMPACTFE_MPI_RANKS (e.g. 2) replaces the rank counts."""
import os
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

TOLERANCE = 1e-10
ACCELERATION_TOLERANCE = 1e-7
SKIP = 77

# Open MPI on one CI machine, possibly as root in a container: allow root, more ranks than
# cores (waiting ranks yield the core instead of spinning), and no cross-memory-attach (ptrace
# is often not permitted there).
MPI_ENV = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_rmaps_base_oversubscribe": "1",
    "OMPI_MCA_btl_vader_single_copy_mechanism": "none",
    "OMPI_MCA_mpi_yield_when_idle": "1",
    "OMP_NUM_THREADS": "1",
}


def run(command, outdir, fresh=True):
    if fresh:
        shutil.rmtree(outdir, ignore_errors=True)
        os.makedirs(outdir)
    env = dict(os.environ, **MPI_ENV)
    p = subprocess.run(command, capture_output=True, text=True, env=env, timeout=900)
    if p.returncode != 0:
        sys.exit(f"FAIL {' '.join(command)}: exit {p.returncode}\n{p.stdout}\n{p.stderr}")
    return p.stdout


def datasets(path):
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f":
                out[name] = obj[()]
        f.visititems(visit)
    return out


FIGURES = ("n_masters", "n_slaves", "n_constrained", "n_load_vectors", "matrices",
           "total_mass_x", "total_mass_y", "total_mass_z", "master_mass_x", "master_mass_y",
           "master_mass_z")


def generation_figures(directory):
    """The summary figures of every superelement generation pass in the results files of a
    directory: {(file, group): {attribute: value}}."""
    out = {}
    for f in sorted(os.listdir(directory)):
        if not f.endswith(".h5") or f.endswith(".sub.h5"):
            continue
        with h5py.File(os.path.join(directory, f), "r") as h:
            for group in h:
                attrs = h[group].attrs
                if group.startswith("analysis_") and "superelement_name" in attrs:
                    out[(f, group)] = {k: float(attrs[k]) for k in FIGURES if k in attrs}
    return out


def check_figures(reference, result, n):
    """Rank 0's results file holds the figures of every generation pass, also of those another
    rank ran (docs/scaling.md, "Substructures in parallel")."""
    out = []
    for key, want in reference.items():
        got = result.get(key, {})
        for k, v in want.items():
            if k not in got or abs(got[k] - v) > 1e-10 * max(1.0, abs(v)):
                out.append(f"{n} ranks: {key[0]} {key[1]} {k} = {got.get(k)} instead of {v}")
    return out


def n_elements(directory, name):
    with h5py.File(os.path.join(directory, name + ".h5"), "r") as f:
        return len(f["model/element_ids"])


SPLIT = re.compile(r"element assembly split over (\d+) MPI ranks \(METIS column partition\): "
                   r"owned ([\d + ]+) = (\d+) of (\d+) elements; evaluated for the matrix "
                   r"([\d + ]+), for the force vectors ([\d + ]+) \(owned plus neighbours\); "
                   r"element assembly seconds per rank ([\d.+ ]+) \(CPU ([\d.+ ]+)\)")


def check_split(stdout, n, elements):
    """The summary line of the split: every rank owned a non-empty proper subset of the
    elements, the owned sets add up to the model's elements, and each rank evaluated fewer
    elements than the model has (its own and a layer of neighbours)."""
    lines = SPLIT.findall(stdout)
    if not lines:
        return [f"{n} ranks: no 'element assembly split' line in the summary"]
    out = []
    for ranks, owned, total, count, matrix, vectors, seconds, cpu in lines:
        owned = [int(x) for x in owned.split(" + ")]
        evaluated = [int(x) for x in vectors.split(" + ")]
        matrix = [int(x) for x in matrix.split(" + ")]
        print(f"  {n} ranks: elements owned {owned}, evaluated {evaluated} (matrix {matrix}) of "
              f"{elements}; element assembly s per rank {seconds} (CPU {cpu})")
        if int(ranks) != n or len(owned) != n or len(evaluated) != n:
            out.append(f"{n} ranks: split over {ranks} ranks")
        if sum(owned) != elements or int(total) != elements or int(count) != elements:
            out.append(f"{n} ranks: owned elements {owned} do not add up to {elements}")
        if any(o <= 0 or o >= elements for o in owned):
            out.append(f"{n} ranks: a rank owned no element or all of them: {owned}")
        if any(not (o <= v and m <= v < elements) for o, m, v in zip(owned, matrix, evaluated)):
            out.append(f"{n} ranks: evaluated {matrix} / {evaluated} elements, owned {owned}")
    return out


def main():
    args = sys.argv[1:]
    extra = []
    if "--" in args:
        extra = args[args.index("--") + 1:]
        args = args[:args.index("--")]
    ranks = [1, 2, 4]
    if "--ranks" in args:
        i = args.index("--ranks")
        ranks = [int(r) for r in args[i + 1].split(",")]
        del args[i:i + 2]
    # IMPACTFE_MPI_RANKS (e.g. "2") replaces the rank counts: the sanitizer suite looks for memory
    # errors, which one distributed rank count exercises (scripts/test-sanitizers.sh).
    if os.environ.get("IMPACTFE_MPI_RANKS"):
        ranks = [int(r) for r in os.environ["IMPACTFE_MPI_RANKS"].split(",")]
    tolerance = TOLERANCE
    if "--tolerance" in args:
        i = args.index("--tolerance")
        tolerance = float(args[i + 1])
        del args[i:i + 2]
    # The deck's element assembly must be split by rank (docs/scaling.md, "Element assembly split
    # by rank"): on n > 1 ranks the summary's per-rank element counts are checked.
    expect_split = "--expect-split" in args
    if expect_split:
        args.remove("--expect-split")
    pre = None
    if "--pre" in args:
        i = args.index("--pre")
        pre = os.path.abspath(args[i + 1])
        del args[i:i + 2]
    binary, deck, out = args[0], os.path.abspath(args[1]), args[2]
    mpirun = shutil.which("mpirun")
    module = os.path.join(os.path.dirname(os.path.abspath(binary)), "libimpactfe_mumps.so")
    if not mpirun or not os.path.exists(module):
        print(f"SKIP: {'mpirun' if not mpirun else module} not found "
              "(scripts/install-deps.sh installs libmumps-dev, libopenmpi-dev, openmpi-bin)")
        sys.exit(SKIP)
    name = os.path.splitext(os.path.basename(deck))[0]
    root = os.path.join(out, name + ("_" + "_".join(a.strip("-") for a in extra) if extra else ""))
    reference_dir = os.path.join(root, "cholmod")
    # The MUMPS options (--mumps-ooc, ...) are for the MUMPS runs only.
    common = [a for a in extra if not a.startswith("--mumps")]
    if pre:
        run([binary, "run", pre, "-o", reference_dir] + common, reference_dir)
    run([binary, "run", deck, "-o", reference_dir] + common, reference_dir, fresh=pre is None)
    reference = datasets(os.path.join(reference_dir, name + ".h5"))
    superelements = sorted(f for f in os.listdir(reference_dir) if f.endswith(".sub.h5"))
    for f in superelements:
        reference.update({f + ":" + k: v for k, v in
                          datasets(os.path.join(reference_dir, f)).items()})
    failures = []
    # Without the refinement (--mumps-no-refine) several ranks are not bitwise repeatable: one
    # run per rank count, checked against CHOLMOD only.
    repeat = "--mumps-no-refine" not in extra
    for n in ranks:
        results = []
        for attempt in (1, 2) if repeat else (1,):
            outdir = os.path.join(root, f"mumps{n}_{attempt}")
            mumps = [mpirun, "-n", str(n), binary, "run"]
            if pre:
                run(mumps + [pre, "-o", outdir, "--solver", "mumps"] + extra, outdir)
            stdout = run(mumps + [deck, "-o", outdir, "--solver", "mumps"] + extra, outdir,
                         fresh=pre is None)
            if f"MUMPS on {n} MPI rank(s)" not in stdout:
                failures.append(f"{n} ranks: the summary does not name MUMPS on {n} ranks")
            if expect_split and n > 1:
                failures += check_split(stdout, n, n_elements(reference_dir, name))
            # Several generation passes in the deck: the log names the rank of each.
            if superelements and not pre and n > 1:
                with open(os.path.join(outdir, name + ".log")) as log:
                    generated = log.read().count("generated by rank")
                if generated < len(superelements):
                    failures.append(f"{n} ranks: the log names the generating rank of "
                                    f"{generated} of {len(superelements)} superelements")
            if superelements:
                failures += check_figures(generation_figures(reference_dir),
                                          generation_figures(outdir), n)
            result = datasets(os.path.join(outdir, name + ".h5"))
            for f in superelements:
                result.update({f + ":" + k: v for k, v in
                               datasets(os.path.join(outdir, f)).items()})
            results.append(result)
            # Only rank 0 writes into the output directory: the files of a one-process run.
            if sorted(os.listdir(outdir)) != sorted(os.listdir(reference_dir)):
                failures.append(f"{n} ranks: files {sorted(os.listdir(outdir))} instead of "
                                f"{sorted(os.listdir(reference_dir))}")
        a, b = results if repeat else (results[0], results[0])
        worst = worst_superelement = 0.0
        for path, y in reference.items():
            x = a.get(path)
            if x is None or x.shape != y.shape:
                failures.append(f"{n} ranks: {path} missing or of another shape")
                continue
            if not np.array_equal(x, b[path], equal_nan=True):
                failures.append(f"{n} ranks: {path} differs between two identical runs")
            if not np.array_equal(np.isfinite(x), np.isfinite(y)):
                failures.append(f"{n} ranks: {path} NaN pattern differs")
                continue
            both = np.isfinite(y)
            if not both.any():
                continue
            peak = np.max(np.abs(y[both]))
            diff = np.max(np.abs(x[both] - y[both]))
            rel = diff / peak if peak > 0 else diff
            limit = TOLERANCE if ".sub.h5:" in path else tolerance
            if path.endswith("/A"):
                limit = max(limit, ACCELERATION_TOLERANCE)
            if ".sub.h5:" in path:
                worst_superelement = max(worst_superelement, rel)
            elif not path.endswith("/A"):
                worst = max(worst, rel)
            if rel > limit:
                failures.append(f"{n} ranks: {path} {rel:.2e} relative (limit {limit:g})")
        print(f"{name} {' '.join(extra)}: {n} rank(s): {len(reference)} arrays, largest relative "
              f"difference to CHOLMOD {worst:.2e} (accelerations excluded)"
              + (f", superelement files {worst_superelement:.2e}" if superelements else "")
              + (", repeat bitwise equal" if repeat else ""))
    if failures:
        sys.exit("FAIL " + name + ": " + "; ".join(failures))
    # A passing case's files go (CI disk); IMPACTFE_KEEP_TEST_OUTPUT=1 keeps them.
    if not os.environ.get("IMPACTFE_KEEP_TEST_OUTPUT"):
        shutil.rmtree(root, ignore_errors=True)
    print("OK")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""A failure on one MPI rank ends every rank (docs/scaling.md, Errors), never a hang:
- IMPACTFE_TEST_FAIL_RANK=r (a test hook honoured only by the MPI module) makes rank r alone fail
  at its first factorization while the other ranks wait for it inside MUMPS: mpirun must end
  within the time limit with the failing rank's exit status (2: the solution failed), the error
  message printed exactly once and the note that the rank failed alone; for r = 1 (a rank whose
  terminal output is otherwise discarded) and r = 0;
- a deck error that every rank meets (a malformed deck) ends every rank with status 1 and the
  message printed once, without the abort (the ranks agree on the status).
Exit 77 (CTest: skipped) when mpirun or the MUMPS module is missing.

usage: fail_one_rank.py IMPACTFE STATIC_DECK MALFORMED_DECK OUTDIR"""
import os
import shutil
import subprocess
import sys
import time

from compare_mumps import MPI_ENV, SKIP

TIME_LIMIT = 60  # seconds; a hang is a failure


def run(command, outdir, env_extra):
    shutil.rmtree(outdir, ignore_errors=True)
    env = dict(os.environ, **MPI_ENV, **env_extra)
    start = time.monotonic()
    try:
        p = subprocess.run(command, capture_output=True, text=True, env=env, timeout=TIME_LIMIT)
    except subprocess.TimeoutExpired:
        sys.exit(f"FAIL {' '.join(command)}: no exit within {TIME_LIMIT} s (a hang)")
    return p.returncode, p.stdout + p.stderr, time.monotonic() - start


def main():
    binary, deck, malformed, out = sys.argv[1:5]
    mpirun = shutil.which("mpirun")
    module = os.path.join(os.path.dirname(os.path.abspath(binary)), "libimpactfe_mumps.so")
    if not mpirun or not os.path.exists(module):
        print(f"SKIP: {'mpirun' if not mpirun else module} not found")
        sys.exit(SKIP)
    failures = []
    for rank in (1, 0):
        outdir = os.path.join(out, f"fail_rank{rank}")
        status, text, seconds = run([mpirun, "-n", "2", binary, "run", deck, "-o", outdir,
                                     "--solver", "mumps"], outdir,
                                    {"IMPACTFE_TEST_FAIL_RANK": str(rank)})
        message = f"test failure on rank {rank} only"
        print(f"rank {rank} fails alone: exit {status} after {seconds:.1f} s, message printed "
              f"{text.count(message)} time(s)")
        if status != 2:
            failures.append(f"rank {rank} failing alone: exit status {status}, expected 2")
        if text.count(message) != 1:
            failures.append(f"rank {rank} failing alone: the message appears "
                            f"{text.count(message)} times:\n{text}")
        if f"rank {rank} of 2 failed alone" not in text:
            failures.append(f"rank {rank} failing alone: no note that it failed alone:\n{text}")
    outdir = os.path.join(out, "fail_all")
    status, text, seconds = run([mpirun, "-n", "2", binary, "run", malformed, "-o", outdir,
                                 "--solver", "mumps"], outdir, {})
    errors = [line for line in text.splitlines() if line.startswith("error: ")]
    print(f"every rank fails: exit {status} after {seconds:.1f} s, {len(errors)} error line(s)")
    if status != 1 or len(errors) != 1 or "failed alone" in text or "MPI_ABORT" in text:
        failures.append(f"every rank failing: exit {status}, expected 1 with one error line and "
                        f"no abort:\n{text}")
    if failures:
        sys.exit("FAIL: " + "\n".join(failures))
    print("OK")


if __name__ == "__main__":
    main()

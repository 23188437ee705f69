#!/usr/bin/env python3
"""Runs one malformed deck through the CLI and checks the error report.

usage: run_malformed.py IMPACTFE_BINARY DECK OUTDIR

The deck's first line states what must happen:
    ! EXPECT-ERROR: <LINE> <COMMAND>: <message fragment>
The run must exit with status 1 and stderr must contain "<deck file>:<LINE>: <COMMAND>:" and the
fragment (the CLI prints InputError::what(), "FILE:LINE: COMMAND: message", after "error: ").
The deck file is matched by its base name so that relative and absolute paths both pass.
"""
import os
import re
import subprocess
import sys

HEADER = re.compile(r"^!\s*EXPECT-ERROR:\s*(\d+)\s+(\S+):\s*(.+?)\s*$")


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    binary, deck, outdir = argv[1], argv[2], argv[3]
    with open(deck, encoding="utf-8", errors="replace") as f:
        first = f.readline()
    m = HEADER.match(first)
    if not m:
        print(f"{deck}: first line is not '! EXPECT-ERROR: <line> <COMMAND>: <fragment>'",
              file=sys.stderr)
        return 2
    line, command, fragment = m.group(1), m.group(2), m.group(3)
    stem = os.path.splitext(os.path.basename(deck))[0]
    out = os.path.join(outdir, stem)
    os.makedirs(out, exist_ok=True)
    proc = subprocess.run([binary, "run", deck, "-o", out], capture_output=True, text=True,
                          timeout=120)
    failures = []
    if proc.returncode != 1:
        failures.append(f"exit status {proc.returncode}, expected 1")
    location = f"{os.path.basename(deck)}:{line}: {command}:"
    if location not in proc.stderr:
        failures.append(f"stderr lacks the location '{location}'")
    if fragment not in proc.stderr:
        failures.append(f"stderr lacks the message fragment '{fragment}'")
    if failures:
        print(f"FAIL {deck}", file=sys.stderr)
        for f in failures:
            print(f"  - {f}", file=sys.stderr)
        print("---- stderr ----\n" + proc.stderr, file=sys.stderr)
        return 1
    print(f"ok {deck}: {location} {fragment}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

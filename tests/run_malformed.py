#!/usr/bin/env python3
"""Runs one malformed deck through the CLI and checks the error report.

usage: run_malformed.py IMPACTFE_BINARY DECK OUTDIR

The deck's first line states what must happen:
    ! EXPECT-ERROR: <LINE> <COMMAND>: <message fragment>
optionally followed by
    ! EXPECT-STATUS: <exit status>          (default 1: deck or model error; 2: solution failure)
    ! EXPECT-ALSO: <another message fragment>   (any number)
The run must exit with that status and stderr must contain "<deck file>:<LINE>: <COMMAND>:" and
every fragment (the CLI prints the error's what(), "FILE:LINE: COMMAND: message", after
"error: "); it must never crash (a signal) or hang. The deck file is matched by its base name so
that relative and absolute paths both pass.
"""
import os
import re
import subprocess
import sys

HEADER = re.compile(r"^!\s*EXPECT-ERROR:\s*(\d+)\s+(\S+):\s*(.+?)\s*$")
STATUS = re.compile(r"^!\s*EXPECT-STATUS:\s*(\d+)\s*$")
ALSO = re.compile(r"^!\s*EXPECT-ALSO:\s*(.+?)\s*$")


def main(argv):
    if len(argv) != 4:
        print(__doc__, file=sys.stderr)
        return 2
    binary, deck, outdir = argv[1], argv[2], argv[3]
    with open(deck, encoding="utf-8", errors="replace") as f:
        lines = f.read().splitlines()
    first = lines[0] if lines else ""
    m = HEADER.match(first)
    if not m:
        print(f"{deck}: first line is not '! EXPECT-ERROR: <line> <COMMAND>: <fragment>'",
              file=sys.stderr)
        return 2
    line, command, fragment = m.group(1), m.group(2), m.group(3)
    status, fragments = 1, [fragment]
    for extra in lines[1:]:
        if (sm := STATUS.match(extra)):
            status = int(sm.group(1))
        elif (am := ALSO.match(extra)):
            fragments.append(am.group(1))
        elif not extra.startswith("!"):
            break
    stem = os.path.splitext(os.path.basename(deck))[0]
    out = os.path.join(outdir, stem)
    os.makedirs(out, exist_ok=True)
    proc = subprocess.run([binary, "run", deck, "-o", out], capture_output=True, text=True,
                          timeout=120)
    failures = []
    if proc.returncode != status:
        failures.append(f"exit status {proc.returncode}, expected {status}")
    location = f"{os.path.basename(deck)}:{line}: {command}:"
    if location not in proc.stderr:
        failures.append(f"stderr lacks the location '{location}'")
    for f in fragments:
        if f not in proc.stderr:
            failures.append(f"stderr lacks the message fragment '{f}'")
    if failures:
        print(f"FAIL {deck}", file=sys.stderr)
        for f in failures:
            print(f"  - {f}", file=sys.stderr)
        print("---- stderr ----\n" + proc.stderr, file=sys.stderr)
        return 1
    print(f"ok {deck}: exit {status}, {location} {' | '.join(fragments)}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

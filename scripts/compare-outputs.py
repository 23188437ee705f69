#!/usr/bin/env python3
"""Runs every regression deck (tests/decks/**/*.inp), verification deck (tests/verification/*.inp)
and example (examples/*.inp) with two impactfe binaries and compares what they write: the exit
status, stdout and stderr, every file in the output directory (HDF5 files dataset by dataset and
attribute by attribute, bit for bit; other files byte for byte), and for the helmet example the
report page (`impactfe report`) and both VTK exports (`impactfe export`, vtkhdf and vtu).

Usage: compare-outputs.py REFERENCE_BINARY CANDIDATE_BINARY WORKDIR [--only SUBSTRING ...]
                          [--jobs N]

Durations in text ("0.062 s") are masked; other outputs that differ between two runs of the same
binary (dates, the commit) are found by running the reference twice and are left out of the
comparison; they are counted. The
reference runs are kept in WORKDIR/reference{1,2} and reused when present (delete them after a
change of the reference binary). Exit status 0 when every deck gives the same outputs.
"""
import argparse
import concurrent.futures
import json
import os
import pathlib
import re
import shutil
import subprocess
import sys

import h5py
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
HELMET = ROOT / "examples" / "helmet_full.inp"


def decks(only):
    found = sorted(ROOT.glob("tests/decks/**/*.inp")) + sorted(
        ROOT.glob("tests/verification/*.inp")) + sorted(ROOT.glob("examples/*.inp"))
    if only:
        found = [d for d in found if any(s in str(d) for s in only)]
    return found


def key_of(deck):
    return str(deck.relative_to(ROOT)).replace("/", "__")


def run_one(binary, deck, out):
    """Runs the deck into `out` (fresh) and, for the helmet, its report and exports."""
    if out.exists():
        shutil.rmtree(out)
    work = out / "run"
    work.mkdir(parents=True)
    try:
        r = subprocess.run([binary, "run", str(deck), "-o", str(work)], capture_output=True,
                           text=True, cwd=work, timeout=3600)
        status, stdout, stderr = r.returncode, r.stdout, r.stderr
    except subprocess.TimeoutExpired:
        status, stdout, stderr = "timeout", "", ""
    (out / "status.txt").write_text(str(status) + "\n")
    (out / "stdout.txt").write_text(stdout)
    (out / "stderr.txt").write_text(stderr)
    if deck == HELMET and status == 0:
        h5 = work / "helmet_full.h5"
        post = out / "post"
        post.mkdir()
        for args in (["report", str(h5), "-o", str(post / "helmet.html")],
                     ["export", str(h5), "-o", str(post / "vtkhdf"), "--format", "vtkhdf"],
                     ["export", str(h5), "-o", str(post / "vtu"), "--format", "vtu"]):
            r = subprocess.run([binary] + args, capture_output=True, text=True, cwd=post)
            (post / (args[0] + "_" + pathlib.Path(args[3]).name + ".status")).write_text(
                "%d\n%s" % (r.returncode, r.stderr))
    return deck


def h5_items(path):
    """name -> ('dataset', array) or ('attr', value), for every dataset and attribute."""
    items = {}

    def visit(name, obj):
        for a, v in obj.attrs.items():
            items[name + "@" + a] = ("attr", np.asarray(v))
        if isinstance(obj, h5py.Dataset):
            items[name] = ("dataset", obj[()])

    with h5py.File(path, "r") as f:
        for a, v in f.attrs.items():
            items["/@" + a] = ("attr", np.asarray(v))
        f.visititems(visit)
    return items


def same_value(a, b):
    a, b = np.asarray(a), np.asarray(b)
    if a.shape != b.shape or a.dtype != b.dtype:
        return False
    if a.dtype.kind in "fc":  # bit for bit, NaN included
        return a.tobytes() == b.tobytes()
    return np.array_equal(a, b)


TIMING = re.compile(r"\b\d+(\.\d+)?(e[-+]?\d+)? (s|ms)\b")


REPORT_DATA = re.compile(r'<script type="application/json" id="impactfe-data">(.*?)</script>',
                         re.S)


def flat_json(value, path=""):
    """(path, leaf) pairs of a JSON value."""
    if isinstance(value, dict):
        for k, v in value.items():
            yield from flat_json(v, path + "/" + k)
    elif isinstance(value, list):
        yield (path + "#len", len(value))
        for i, v in enumerate(value):
            yield from flat_json(v, "%s[%d]" % (path, i))
    else:
        yield (path, value)


def masked(text, workdir_names):
    """The text without the run's directory and without durations ("0.062 s", "0.07 ms")."""
    for name in workdir_names:
        text = text.replace(name, "<OUT>")
    return TIMING.sub("<time>", text)


def file_units(root):
    """Comparable units of one run: (relative path, kind) -> value."""
    units = {}
    for p in sorted(root.rglob("*")):
        if not p.is_file():
            continue
        rel = str(p.relative_to(root))
        if p.suffix in (".h5", ".vtkhdf", ".hdf5"):
            try:
                for name, (kind, value) in h5_items(p).items():
                    units[(rel, name)] = value
            except OSError:
                units[(rel, "<bytes>")] = p.read_bytes()
        elif p.suffix == ".html":
            text = masked(p.read_text(errors="replace"), [str(root)])
            # The report's data: compared item by item, durations (*_seconds) left out.
            m = REPORT_DATA.search(text)
            if m:
                for path, value in flat_json(json.loads(m.group(1))):
                    if not path.endswith("_seconds"):
                        units[(rel, "data" + path)] = value
                text = text[:m.start(1)] + text[m.end(1):]
            for i, line in enumerate(text.splitlines()):
                units[(rel, i)] = line
        elif p.suffix in (".txt", ".log", ".out", ".csv", ".status", ".svg", ".vtu",
                          ".pvd", ".lis", ".dat", ".json", ".py", ""):
            text = masked(p.read_text(errors="replace"), [str(root)])
            for i, line in enumerate(text.splitlines()):
                units[(rel, i)] = line
            units[(rel, "<lines>")] = len(text.splitlines())
        else:
            units[(rel, "<bytes>")] = p.read_bytes()
    return units


def equal(a, b):
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        return same_value(a, b)
    return a == b


def compare(ref1, ref2, cand):
    """(differences, volatile count) between the candidate and the reference run."""
    u1, u2, uc = file_units(ref1), file_units(ref2), file_units(cand)
    volatile = {k for k in u1 if k in u2 and not equal(u1[k], u2[k])}
    diffs = []
    for k in sorted(set(u1) | set(uc), key=str):
        if k in volatile:
            continue
        if k not in uc:
            diffs.append("missing in candidate: %s %s" % k)
        elif k not in u1:
            diffs.append("only in candidate: %s %s" % k)
        elif not equal(u1[k], uc[k]):
            v1, vc = u1[k], uc[k]
            if isinstance(v1, str):
                diffs.append("%s line %s:\n    - %s\n    + %s" % (k[0], k[1], v1, vc))
            else:
                diffs.append("%s %s differs" % k)
    return diffs, len(volatile)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("reference")
    ap.add_argument("candidate")
    ap.add_argument("workdir")
    ap.add_argument("--only", nargs="*", default=[])
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--compare-only", action="store_true",
                    help="compare the runs kept in WORKDIR without running anything")
    ap.add_argument("--reference-only", action="store_true",
                    help="only run the reference twice (to compare candidates later)")
    a = ap.parse_args()
    work = pathlib.Path(a.workdir).resolve()
    todo = decks(a.only)
    runs = []
    for deck in todo:
        k = key_of(deck)
        for tag in ("reference1", "reference2"):
            if not (work / tag / k / "status.txt").exists():
                runs.append((a.reference, deck, work / tag / k))
        if not a.reference_only:
            runs.append((a.candidate, deck, work / "candidate" / k))
    env_threads = {"OMP_NUM_THREADS": "1"}
    os.environ.update(env_threads)
    if a.compare_only:
        runs = []
    with concurrent.futures.ThreadPoolExecutor(a.jobs) as pool:
        list(pool.map(lambda r: run_one(*r), runs))
    if a.reference_only:
        return 0
    same, different, volatile_total = 0, [], 0
    for deck in todo:
        k = key_of(deck)
        diffs, volatile = compare(work / "reference1" / k, work / "reference2" / k,
                                  work / "candidate" / k)
        volatile_total += volatile
        if diffs:
            different.append((deck, diffs))
        else:
            same += 1
    for deck, diffs in different:
        print("DIFFERENT %s" % deck.relative_to(ROOT))
        for d in diffs[:20]:
            print("  " + d)
        if len(diffs) > 20:
            print("  ... %d more" % (len(diffs) - 20))
    print("%d decks: %d with the same outputs, %d different (%d volatile items left out)" %
          (len(todo), same, len(different), volatile_total))
    return 0 if not different else 1


if __name__ == "__main__":
    sys.exit(main())

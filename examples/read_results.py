#!/usr/bin/env python3
"""Read an impactfe results file (<jobname>.h5) with h5py.

Schema: docs/results_file.md. Examples:

    python3 read_results.py crash1.h5                  # summary of the file
    python3 read_results.py crash1.h5 --nsol 2,UX      # time history of node 2 UX as CSV
    python3 read_results.py crash1.h5 --esol 6,SAXL    # element 6 item SAXL
    python3 read_results.py crash1.h5 --gapf 1         # GP gap force 1
    python3 read_results.py modal.h5 --freq            # frequencies of the last modal analysis

The time histories follow the same merge rule as `impactfe post`: analyses in order, finite
values only, a later analysis replaces an earlier value at the same time, sorted by time.
"""
import argparse
import bisect
import math
import sys

import h5py
import numpy as np

NODAL_LABELS = {
    "UX": ("U", 0), "UY": ("U", 1), "UZ": ("U", 2),
    "ROTX": ("U", 3), "ROTY": ("U", 4), "ROTZ": ("U", 5),
    "VX": ("V", 0), "VY": ("V", 1), "VZ": ("V", 2),
    "AX": ("A", 0), "AY": ("A", 1), "AZ": ("A", 2),
    "FX": ("R", 0), "FY": ("R", 1), "FZ": ("R", 2),
    "MX": ("R", 3), "MY": ("R", 4), "MZ": ("R", 5),
}


def text(value):
    """h5py returns variable-length strings as str (h5py >= 3) or bytes."""
    return value.decode() if isinstance(value, bytes) else str(value)


def analyses(f):
    """The /analysis_<k> groups in run order."""
    k = 1
    while f"analysis_{k}" in f:
        yield f[f"analysis_{k}"]
        k += 1


def same_time(a, b):
    return abs(a - b) <= 1e-12 * max(1.0, abs(a), abs(b))


def merge(per_analysis):
    """Merge rule of ResultsReader: later analyses replace values at the same time."""
    merged = []
    for points in per_analysis:
        later = sorted(t for t, _ in points)

        def in_later(t):
            i = bisect.bisect_left(later, t - 2e-12 * max(1.0, abs(t)))
            return i < len(later) and same_time(later[i], t)

        merged = [p for p in merged if not in_later(p[0])]
        merged.extend(points)
    return sorted(merged, key=lambda p: p[0])  # Python's sort is stable


def finite_points(times, values):
    return [(float(t), float(v)) for t, v in zip(times, values) if math.isfinite(v)]


def nodal_series(f, node, lab):
    dataset, col = NODAL_LABELS[lab.upper()]
    node_ids = f["model/node_ids"][:]
    row = int(np.searchsorted(node_ids, node))
    if row >= len(node_ids) or node_ids[row] != node:
        raise SystemExit(f"node {node} is not in the results file")
    out = []
    for an in analyses(f):
        if "time" not in an or dataset not in an:
            continue
        t = an["time"][:]
        values = np.full(len(t), np.nan)
        stored = an[dataset][: len(t), row, col]  # may be shorter than time
        values[: len(stored)] = stored
        out.append(finite_points(t, values))
    return merge(out)


def element_series(f, element, item):
    out = []
    for an in analyses(f):
        if "time" not in an or "elements" not in an:
            continue
        t = an["time"][:]
        for fam in an["elements"].values():
            ids = list(fam["element_ids"][:])
            items = [text(s).upper() for s in fam.attrs["items"]]
            if element not in ids or item.upper() not in items:
                continue
            values = np.full(len(t), np.nan)
            stored = fam["values"][: len(t), ids.index(element), items.index(item.upper())]
            values[: len(stored)] = stored
            out.append(finite_points(t, values))
    return merge(out)


def gap_force_series(f, gap):
    out = []
    for an in analyses(f):
        if "time" not in an or "gap_forces" not in an or gap > an["gap_forces"].shape[1]:
            continue
        t = an["time"][:]
        values = np.full(len(t), np.nan)
        stored = an["gap_forces"][: len(t), gap - 1]
        values[: len(stored)] = stored
        out.append(finite_points(t, values))
    return merge(out)


def summary(f):
    print(f"Title: {text(f.attrs.get('title', ''))}")
    print(f"Nodes: {len(f['model/node_ids'])}  Elements: {len(f['model/element_ids'])}")
    for an in analyses(f):
        n_t = len(an["time"]) if "time" in an else 0
        line = f"{an.name}: {text(an.attrs['kind'])}, status {text(an.attrs['status'])}, {n_t} points"
        if n_t:
            line += f", t = {an['time'][0]:g} .. {an['time'][n_t - 1]:g}"
        print(line)
        if "energy" in an and n_t:
            names = [text(s) for s in an["energy"].attrs["columns"]]
            print("  last energies: " + ", ".join(
                f"{name} {value:g}" for name, value in zip(names, an["energy"][n_t - 1])
                if math.isfinite(value)))
        if "elements" in an:
            print("  element families: " + " ".join(an["elements"].keys()))


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("file")
    parser.add_argument("--nsol", help="NODE,LAB")
    parser.add_argument("--esol", help="ELEM,ITEM")
    parser.add_argument("--gapf", type=int, help="gap number")
    parser.add_argument("--freq", action="store_true", help="modal frequencies")
    args = parser.parse_args(argv)
    with h5py.File(args.file, "r") as f:
        if args.nsol:
            node, lab = args.nsol.split(",")
            series, name = nodal_series(f, int(node), lab), f"N{int(node)}_{lab.upper()}"
        elif args.esol:
            elem, item = args.esol.split(",")
            series, name = element_series(f, int(elem), item), f"E{int(elem)}_{item.upper()}"
        elif args.gapf:
            series, name = gap_force_series(f, args.gapf), f"GAP{args.gapf}"
        elif args.freq:
            modal = [an for an in analyses(f) if "frequencies" in an]
            print("mode,frequency_hz")
            for i, hz in enumerate(modal[-1]["frequencies"][:] if modal else [], start=1):
                print(f"{i},{hz:.10e}")
            return
        else:
            summary(f)
            return
        print(f"time,{name}")
        for t, v in series:
            print(f"{t:.10e},{v:.10e}")


if __name__ == "__main__":
    main(sys.argv[1:])

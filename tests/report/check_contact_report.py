#!/usr/bin/env python3
"""`impactfe report` of a contact model: runs the plate drop (SHELL181 plate, CONTA174 faces, a
rigid TARGE170 floor larger than the plate, /UNITS,SI), writes its report and checks the page's
data against the results read by the Python package: the floor is an overlay that does not set
the view's extent, the contact faces are not drawn, the plate is named by its shells, the contact
pair's force is ΣFN of its elements at every stored time, and the axes carry the SI units.

usage: check_contact_report.py IMPACTFE DECK OUTDIR   (OUTDIR/<stem>.html is kept for the
headless-Chromium test, tests/report/browser_test.cjs ... contact)"""
import base64
import json
import os
import re
import struct
import subprocess
import sys

import impactfe as ife

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def run(args):
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != 0:
        print(p.stdout, p.stderr)
        raise SystemExit(f"{' '.join(args)} exited {p.returncode}")
    return p


def floats(b64):
    raw = base64.b64decode(b64)
    return struct.unpack(f"<{len(raw) // 4}f", raw)


def main():
    binary, deck, out = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
    os.makedirs(out, exist_ok=True)
    stem = os.path.splitext(os.path.basename(deck))[0]
    run([binary, "run", deck, "-o", out])
    results = os.path.join(out, stem + ".h5")
    html_path = os.path.join(out, stem + ".html")
    run([binary, "report", results, "-o", html_path])
    html = open(html_path, encoding="utf-8").read()
    m = re.search(r'<script type="application/json" id="impactfe-data">(.*?)</script>', html, re.S)
    data = json.loads(m.group(1))
    mesh = data["mesh"]
    r = ife.open(results)
    elements = r.elements()
    shells = elements.index[elements["type_name"] == "SHELL181"]
    targets = elements.index[elements["type_name"] == "TARGE170"]

    # Drawn: the shells only (2 triangles each); the floor's quad as an overlay; no CONTA174.
    drawn = {mesh["element_ids"][e] for e in mesh["triangle_element"]}
    check(drawn == set(shells), f"drawn elements are the shells ({len(drawn)} drawn)")
    overlay = {mesh["element_ids"][e] for e in mesh["overlay_element"]}
    check(overlay and overlay <= set(targets), f"overlay is the target floor: {sorted(overlay)}")
    # The view's extent: the plate's nodes, not the 2.5 m floor's corners.
    xyz = floats(mesh["xyz"])
    framed = mesh["framed_nodes"]
    xs = [xyz[3 * i] for i in framed]
    check(len(framed) == 121 and max(xs) - min(xs) < 0.51, f"framed nodes: {len(framed)}")
    names = [b["name"] for b in mesh["bodies"]]
    check(names[0] == "the SHELL181 type 1 mat 1 real 1 part", f"parts: {names}")
    check(any(n.startswith("the rigid target (TARGE170)") for n in names), f"parts: {names}")

    # The pair's force: ΣFN of its CONTA174 elements, at the peak, from the Python reader.
    figs = data["contact_force"]
    check(len(figs) == 1, f"one contact pair ({len(figs)} figures)")
    normal = figs[0]["series"][0]
    t, y = floats(normal["t"]), floats(normal["y"])
    k = max(range(len(y)), key=lambda i: abs(y[i]))
    sets = r.sets()
    stored = sets["time"].to_numpy()  # the page's times are float32: take the stored one
    time = float(stored[abs(stored - t[k]).argmin()])
    expected = r.field("FN", time=time)["FN"].sum()
    check(abs(y[k] - expected) <= 1e-5 * abs(expected), f"ΣFN at t = {t[k]}: {y[k]} vs {expected}")
    check(normal["peak_abs"] > 1e4, f"the plate lands: peak ΣFN {normal['peak_abs']}")
    check(figs[0]["ylabel"] == "Contact force (N)" and figs[0]["xlabel"] == "Time (s)",
          f"SI axes: {figs[0]['xlabel']!r}, {figs[0]['ylabel']!r}")
    check(data["units"]["stress"] == "Pa", f"units: {data['units']}")
    check(data["first_contact_time"] is not None and 0 < data["first_contact_time"] < 0.006,
          f"first contact at {data['first_contact_time']}")
    check(data["gap_status"]["rows"] == [], "contact elements are not gap rows")
    if failures:
        raise SystemExit(f"{len(failures)} check(s) failed")
    print("contact report checks: ok")


if __name__ == "__main__":
    main()

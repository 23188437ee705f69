#!/usr/bin/env python3
"""`impactfe report` end to end: runs the helmet example, writes its report and checks that the
page is self-contained, small, and carries the same numbers as `impactfe post`; options choose
nodes, elements and the direction; a file that is not a results file exits 1 with a clear
message. (Long histories: tests/unit/test_report.cpp, ReportLongHistory.)

usage: check_report.py IMPACTFE HELMET_DECK OUTDIR   (OUTDIR/helmet_full.html is kept for the
headless-Chromium test, tests/report/browser_test.cjs)"""
import base64
import json
import os
import re
import struct
import subprocess
import sys

HELMET_LIMIT = 3_000_000  # bytes: the page must stay a few MB at most

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print("FAIL:", message)


def run(args, expect=0):
    p = subprocess.run(args, capture_output=True, text=True)
    if p.returncode != expect:
        print(p.stdout, p.stderr)
        raise SystemExit(f"{' '.join(args)} exited {p.returncode}, expected {expect}")
    return p


def floats(b64):
    raw = base64.b64decode(b64)
    return struct.unpack(f"<{len(raw) // 4}f", raw)


def page_data(html):
    m = re.search(r'<script type="application/json" id="impactfe-data">(.*?)</script>', html, re.S)
    check(m is not None, "the page embeds its data")
    return json.loads(m.group(1))


def check_self_contained(html, name):
    external = re.findall(r'''(?:src|href)\s*=\s*["']?\s*(?:https?:)?//[^"' >]*''', html, re.I)
    check(not external, f"{name}: no external script/link/image sources (found {external[:3]})")
    check(not re.search(r"<link\b", html, re.I), f"{name}: no <link> elements")
    check(html.count("<script") == 2, f"{name}: exactly the data and the inlined script")


def write_report(impactfe, results, html, *extra):
    p = run([impactfe, "report", results, "-o", html, *extra])
    size = os.path.getsize(html)
    check(html in p.stdout and "MB" in p.stdout, f"report says what it wrote: {p.stdout!r}")
    print(f"{html}: {size} bytes")
    return size


def main():
    impactfe, deck, out = sys.argv[1], os.path.abspath(sys.argv[2]), os.path.abspath(sys.argv[3])
    os.makedirs(out, exist_ok=True)
    run([impactfe, "run", deck, "-o", out])
    results = os.path.join(out, "helmet_full.h5")
    html_path = os.path.join(out, "helmet_full.html")
    size = write_report(impactfe, results, html_path)
    check(size < HELMET_LIMIT, f"helmet report {size} bytes < {HELMET_LIMIT}")
    html = open(html_path, encoding="utf-8").read()
    check_self_contained(html, "helmet")
    data = page_data(html)

    # Every stored point is drawn (190 steps + t = 0 are far below the sampling limit).
    figures = data["figures"]
    titles = [f["title"] for f in figures]
    print("figures:", titles)
    check(len([t for t in titles if t.startswith("Displacement")]) == 2,
          "a displacement figure for each part (head and helmet), as thesis Figs. 5-3-2/5-3-3")
    check(any(t.startswith("Velocity") for t in titles), "velocity figures (Figs. 5-3-4/5-3-5)")
    check(any(t.startswith("Acceleration") for t in titles), "acceleration figures (5-3-6/7)")
    check(any(t.startswith("Stress of element") for t in titles),
          "a stress figure of the most stressed elements")
    check(data["directions"] == ["Z"], f"the drop direction Z is chosen: {data['directions']}")

    # The curves carry the same numbers as `impactfe post` (float32 in the page).
    curves = {s["label"]: s for f in figures for s in f["series"]}
    check("Node 43 UZ" in curves, "the helmet crown (node 43, gap to the ground) is plotted")
    for label in ("Node 43 UZ", "Node 43 AZ"):
        if label not in curves:
            continue
        node, lab = label.split()[1], label.split()[2]
        csv = run([impactfe, "post", results, "--nsol", f"{node},{lab}"]).stdout.split("\n")[1:]
        post = [tuple(map(float, row.split(","))) for row in csv if row]
        t, y = floats(curves[label]["t"]), floats(curves[label]["y"])
        check(len(t) == len(post), f"{label}: {len(t)} points, post has {len(post)}")
        worst = max(abs(a - b[1]) / max(1.0, abs(b[1])) for a, b in zip(y, post))
        check(worst < 1e-6, f"{label}: equals post within float32 ({worst:.2e})")

    check(len(data["gap_status"]["rows"]) == 10, "a status row for each of the 10 COMBIN40 gaps")
    closed = [r for r in data["gap_status"]["rows"] if any(c[1] == 1 for c in r["changes"])]
    check(len(closed) >= 1, "at least one gap closes (the helmet hits the ground)")
    check(len(data["energy"]) >= 1, "the energy balance is stored and shown")
    n_frames = len(data["frames"]["times"])
    check(n_frames == 191, f"every stored time point is a frame of the 3-D view ({n_frames})")
    check(len(data["mesh"]["triangles"]) // 3 >= 72, "the 72 shell triangles are drawn")
    check(len(data["mesh"]["lines"]) // 2 == 10, "the 10 gap elements are drawn as lines")
    names = [f["name"] for f in data["frames"]["fields"]]
    check("SEQV" in names, f"colouring by SEQV is offered: {names}")

    # Options: a chosen node, element and direction.
    chosen = os.path.join(out, "helmet_chosen.html")
    write_report(impactfe, results, chosen, "--node", "43", "--element", "86", "--item", "UZ")
    d = page_data(open(chosen, encoding="utf-8").read())
    check([f["title"] for f in d["figures"]][0] == "Displacement UZ of node 43 vs time",
          "--node 43 --item UZ gives the node's UZ figure")
    check(any(s["label"].startswith("Element 86 ") for f in d["figures"] for s in f["series"]),
          "--element 86 is plotted")

    # Bad input: exit 1 with a clear message.
    bogus = os.path.join(out, "not_results.h5")
    open(bogus, "w").write("not hdf5\n")
    p = run([impactfe, "report", bogus], expect=1)
    check("not an impactfe results file" in p.stderr, f"clear message: {p.stderr!r}")
    p = run([impactfe, "report", os.path.join(out, "missing.h5")], expect=1)
    check("does not exist" in p.stderr, f"clear message: {p.stderr!r}")
    p = run([impactfe, "report", results, "--node", "9999", "-o", os.path.join(out, "x.html")],
            expect=1)
    check("node 9999" in p.stderr, f"unknown node named: {p.stderr!r}")

    print(f"{len(failures)} failed" if failures else "report checks: ok")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Checks the architecture of src/ (docs/architecture.md): every #include of a project header
points to the same layer or a lower one, and no source file exceeds the size cap.

Layers, lowest first. A directory may include from its own layer and any layer below it."""
import pathlib
import re
import sys

LAYERS = ["core", "linalg", "io", "materials", "elements", "time", "geometry", "assembly",
          "nonlinear",
          "reduction", "results", "deck", "analysis", "app"]
MAX_LINES = 800  # soft cap of ../shared/DESIGN.md, enforced for .cpp and .h files

root = pathlib.Path(__file__).resolve().parent.parent / "src"
rank = {name: i for i, name in enumerate(LAYERS)}
include = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
errors = []
for path in sorted(root.rglob("*")):
    if path.suffix not in (".h", ".cpp"):
        continue
    layer = path.relative_to(root).parts[0]
    if layer not in rank:
        errors.append(f"{path.relative_to(root)}: directory '{layer}' is not in the layer list")
        continue
    lines = path.read_text(encoding="utf-8").splitlines()
    if len(lines) > MAX_LINES:
        errors.append(f"{path.relative_to(root)}: {len(lines)} lines (cap {MAX_LINES})")
    for number, line in enumerate(lines, 1):
        m = include.match(line)
        if not m:
            continue
        target = m.group(1).split("/")[0]
        if target not in rank:
            continue  # a sibling header of the same directory, or a generated file
        if rank[target] > rank[layer]:
            errors.append(f"{path.relative_to(root)}:{number}: {layer} includes {m.group(1)} "
                          f"from the higher layer '{target}'")
for e in errors:
    print(e)
print("layer check: " + ("ok" if not errors else f"{len(errors)} problem(s)"))
sys.exit(1 if errors else 0)

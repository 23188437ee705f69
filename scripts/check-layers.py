#!/usr/bin/env python3
"""Checks the architecture of src/ (docs/architecture.md): every #include of a project header
follows an allowed edge between folders, and no source file exceeds the size cap.

ALLOWED lists, for each folder of src/, the other folders whose headers it may include. An edge
that is not listed is an error, so a new dependency is a decision made here, in review, not a
side effect. The graph has no cycles (checked too)."""
import pathlib
import re
import sys

ALLOWED = {
    "core": [],
    "linalg": ["core"],
    "io": ["core"],
    "materials": ["core"],
    "elements": ["core", "io", "materials"],
    "time": ["core"],
    "geometry": ["core", "elements"],
    "assembly": ["core", "elements", "linalg", "time"],
    "nonlinear": ["core", "elements", "linalg", "assembly"],
    "reduction": ["core", "linalg", "assembly", "time"],
    "results": ["core", "io", "elements"],
    # The deck layer builds the model and the list of solution requests, and reads results
    # files for POST1/POST26: never a solver, an assembler or the nonlinear layer. It checks
    # the step-size settings through their owner, time/time_schedule.h, at the command.
    "deck": ["core", "elements", "geometry", "io", "results", "time"],
    # Explicit dynamics (docs/explicit_dynamics.md): the central-difference run over the element
    # sets of the registry, writing the results file; no linear algebra, no assembler.
    "explicit": ["core", "materials", "elements", "results"],
    # The drivers; deck/solution_host.h is the interface through which the deck hands its
    # solution requests to the job session, which implements it.
    "analysis": ["core", "linalg", "io", "materials", "elements", "time", "geometry", "assembly",
                 "nonlinear", "reduction", "results", "deck", "explicit"],
    "app": ["core", "linalg", "time", "results", "deck", "analysis"],
}
# Inside the deck layer, each processor's commands keep their own state (deck/deck_context.h):
# the handler files that may touch each part of DeckReader's state through `r.<part>`. The rest of
# the deck layer reaches it only through these handlers (or the model and the job).
DECK_STATE = {
    "modeling": ["prep7_commands.cpp", "generation_commands.cpp", "material_commands.cpp",
                 "solid_edit_commands.cpp", "contact_commands.cpp", "mesh_commands.cpp",
                 # SAVE/RESUME store the attribute pointers; *GET,Par,ACTIVE,,TYPE reads them.
                 "database_commands.cpp", "get_command.cpp",
                 # EBLOCK sets the attribute pointers of each element record it adds.
                 "cdb_commands.cpp",
                 # EDMP's MAT defaults to the MAT attribute pointer.
                 "explicit_commands.cpp",
                 # CE,R5.0,NODE records continue the equation of the CE,R5.0,DEFI before them.
                 "constraint_equation_commands.cpp"],
    # 4x defines the analysis (KAN) in PREP7; FINISH closes a 4x /STRESS block.
    "solution": ["solution_commands.cpp", "dynamics_commands.cpp", "prep7_commands.cpp",
                 "session_commands.cpp"],
    "scripting": ["parameter_commands.cpp", "array_commands.cpp", "matrix_commands.cpp",
                  "output_commands.cpp", "vector_support.h",
                  # XMLO's encoding, written by /XML.
                  "workbench_commands.cpp"],
    "post": ["post_support.cpp"],
}
MAX_LINES = 800  # soft cap of ../shared/DESIGN.md, enforced for .cpp and .h files


def find_cycle():
    state = {}

    def visit(node, path):
        state[node] = "open"
        for nxt in ALLOWED[node]:
            if state.get(nxt) == "open":
                return path + [node, nxt]
            if nxt not in state:
                found = visit(nxt, path + [node])
                if found:
                    return found
        state[node] = "done"
        return None

    for node in ALLOWED:
        if node not in state:
            found = visit(node, [])
            if found:
                return found
    return None


root = pathlib.Path(__file__).resolve().parent.parent / "src"
include = re.compile(r'^\s*#\s*include\s+"([^"]+)"')
errors = []
cycle = find_cycle()
if cycle:
    errors.append("the allowed edges form a cycle: " + " -> ".join(cycle))
for path in sorted(root.rglob("*")):
    if path.suffix not in (".h", ".cpp"):
        continue
    folder = path.relative_to(root).parts[0]
    if folder not in ALLOWED:
        errors.append(f"{path.relative_to(root)}: folder '{folder}' is not in scripts/check-layers.py")
        continue
    lines = path.read_text(encoding="utf-8").splitlines()
    if len(lines) > MAX_LINES:
        errors.append(f"{path.relative_to(root)}: {len(lines)} lines (cap {MAX_LINES})")
    for number, line in enumerate(lines, 1):
        m = include.match(line)
        if not m:
            continue
        target = m.group(1).split("/")[0]
        if target not in ALLOWED or target == folder:
            continue  # a sibling header of the same folder, or a generated file
        if target not in ALLOWED[folder]:
            errors.append(f"{path.relative_to(root)}:{number}: {folder} includes {m.group(1)}: "
                          f"'{folder}' -> '{target}' is not an allowed edge")
state_use = re.compile(r"\br\.(" + "|".join(DECK_STATE) + r")\b")
for path in sorted((root / "deck").glob("*")):
    for number, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        for m in state_use.finditer(line):
            if path.name not in DECK_STATE[m.group(1)]:
                errors.append(f"deck/{path.name}:{number}: uses r.{m.group(1)}, the state of "
                              "another processor's commands (DECK_STATE in scripts/check-layers.py)")
# The test binary is a unity build (cmake/unity.cmake): each test file keeps its code in a
# namespace named after the file, so that file-scope helpers of two files never collide.
tests = root.parent / "tests"
for path in sorted(list((tests / "unit").glob("test_*.cpp")) +
                   list((tests / "regression").glob("test_*.cpp"))):
    text = path.read_text(encoding="utf-8")
    if not re.search(r"^namespace (impactfe(::\w+)*::)?" + path.stem + r" \{$", text, re.M):
        errors.append(f"{path.relative_to(root.parent)}: its code is not in a namespace named "
                      f"after the file ('namespace impactfe::{path.stem} {{' or "
                      f"'namespace {path.stem} {{'; tests/CMakeLists.txt says why)")
for e in errors:
    print(e)
print("layer check: " + ("ok" if not errors else f"{len(errors)} problem(s)"))
sys.exit(1 if errors else 0)

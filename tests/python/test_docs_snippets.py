"""Every Python snippet of the documentation runs against the file it names: the ```python
blocks of README.md, python/README.md and docs/*.md, the literal blocks (after "::") of the
package's docstrings, and the `python3 <script> ... <file>.h5` lines of the ```bash blocks.
The blocks of one page run in order in one fresh interpreter (a page reads like a session), in
a directory where each results file a snippet names (`out/helmet_full.h5`, `crash1.h5`) is the
one its deck makes. A snippet that names a file no deck here makes fails: add the deck to
DECKS_OF."""
import ast
import glob
import json
import os
import re
import subprocess
import sys

import pytest

from conftest import EXAMPLES, ROOT

#: Results file name -> the deck that makes it (examples/<name>.inp unless said).
DECKS_OF = {name: os.path.join(EXAMPLES, name[:-3] + ".inp") for name in (
    "helmet_full.h5", "crash1.h5", "crash3.h5", "plate_drop.h5", "plate_modes.h5")}
DECKS_OF["explicit_contact_blocks_solid164.h5"] = os.path.join(
    ROOT, "tests", "verification", "explicit_contact_blocks_solid164.inp")
PAGES = ["README.md", "python/README.md", *sorted(
    os.path.relpath(p, ROOT) for p in glob.glob(os.path.join(ROOT, "docs", "**", "*.md"),
                                                recursive=True))]
FENCE = re.compile(r"^```(\w*)\n(.*?)^```", re.S | re.M)
H5_NAME = re.compile(r"""["'\s]((?:[\w.-]+/)*[\w.-]+\.h5)\b""")


def _markdown_snippets(page):
    """(kind, code, first line number) of the page's python blocks and python3 command lines."""
    with open(os.path.join(ROOT, page)) as f:
        content = f.read()
    out = []
    for m in FENCE.finditer(content):
        line = content.count("\n", 0, m.start()) + 2
        if m.group(1) == "python":
            out.append(("python", m.group(2), line))
        elif m.group(1) == "bash":
            for i, cmd in enumerate(m.group(2).splitlines()):
                if cmd.startswith("python3 ") and H5_NAME.search(cmd):
                    out.append(("command", cmd.split("#")[0].strip(), line + i))
    return out


def _docstring_snippets():
    """(page, [("python", code, line)]) of the literal blocks in impactfe's docstrings."""
    pages = []
    for path in sorted(glob.glob(os.path.join(ROOT, "python", "impactfe", "*.py"))):
        with open(path) as f:
            tree = ast.parse(f.read())
        blocks = []
        for node in ast.walk(tree):
            if not isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef)):
                continue
            doc = ast.get_docstring(node, clean=True)
            if not doc or "::\n" not in doc:
                continue
            for chunk in doc.split("::\n")[1:]:
                lines = []
                for text in chunk.splitlines():
                    if text and not text.startswith(" "):
                        break
                    lines.append(text[4:])
                blocks.append(("python", "\n".join(lines).strip() + "\n", getattr(node, "lineno", 1)))
        if blocks:
            pages.append((os.path.relpath(path, ROOT), blocks))
    return pages


SNIPPETS = [(page, _markdown_snippets(page)) for page in PAGES] + _docstring_snippets()
SNIPPETS = [(page, blocks) for page, blocks in SNIPPETS if blocks]

RUNNER = r"""
import json, sys, traceback
namespace = {"__name__": "__main__"}
for n, (code, where) in enumerate(json.load(sys.stdin)):
    try:
        exec(compile(code, where, "exec"), namespace)
    except BaseException:
        print(f"SNIPPET FAILED: {where}", file=sys.stderr)
        traceback.print_exc()
        sys.exit(1)
"""


def test_the_documentation_has_snippets():
    python = sum(k == "python" for _, blocks in SNIPPETS for k, _, _ in blocks)
    commands = sum(k == "command" for _, blocks in SNIPPETS for k, _, _ in blocks)
    pages = {page for page, _ in SNIPPETS}
    assert {"README.md", "python/README.md", "docs/python.md", "docs/results_file.md",
            "python/impactfe/__init__.py"} <= pages, pages
    assert python >= 12 and commands >= 1, (python, commands)


@pytest.mark.parametrize("page,blocks", SNIPPETS, ids=[page for page, _ in SNIPPETS])
def test_snippets_run(page, blocks, run_deck, helmet, tmp_path):
    names = {m for _, code, _ in blocks for m in H5_NAME.findall(" " + code)}
    for name in sorted(names):
        base = os.path.basename(name)
        assert base in DECKS_OF, f"{page} names {name}: no deck in DECKS_OF makes it"
        made = helmet if base == "helmet_full.h5" else run_deck(DECKS_OF[base], base[:-3])
        os.makedirs(tmp_path / os.path.dirname(name), exist_ok=True)
        if not os.path.exists(tmp_path / name):
            os.symlink(made, tmp_path / name)
    env = dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python"))
    python = [(code, f"{page}:{line}") for kind, code, line in blocks if kind == "python"]
    if python:
        p = subprocess.run([sys.executable, "-c", RUNNER], input=json.dumps(python), cwd=tmp_path,
                           env=env, capture_output=True, text=True, timeout=300)
        assert p.returncode == 0, p.stderr
        assert "Warning" not in p.stderr, p.stderr  # pandas' and numpy's warnings included
    for kind, cmd, line in blocks:
        if kind != "command":
            continue
        args = cmd.split()
        args[0] = sys.executable
        args[1] = os.path.join(ROOT, args[1])  # the script, from the checkout
        p = subprocess.run(args, cwd=tmp_path, env=env, capture_output=True, text=True,
                           timeout=300)
        assert p.returncode == 0, f"{page}:{line}: {cmd}\n{p.stdout}{p.stderr}"

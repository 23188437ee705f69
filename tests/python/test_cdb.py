"""CDB archives end to end: a model written by CDWRITE and read back by CDREAD solves to the same
bits as the deck that built it; a public archive written by Workbench (../shared/cdb) reads
with its numbers as written."""
import os
import re

import numpy as np

import impactfe
from conftest import ROOT, run

SHARED_CDB = os.path.join(os.path.dirname(ROOT), "shared", "cdb")

MODEL = """/PREP7
ET,1,SOLID185
ET,2,COMBIN14
R,2,5.0E6
MP,EX,1,2.1E11
MP,PRXY,1,0.3
MP,DENS,1,7850
BLOCK,0,1,0,0.1,0,0.1
ESIZE,0.05
TYPE,1
MAT,1
VMESH,ALL
NSEL,S,LOC,X,0
CM,ROOT,NODE
NSEL,S,LOC,X,1
CM,TIP,NODE
ALLSEL
*GET,NMAX,NODE,0,NUM,MAX
N,NMAX+1,1.2,0.05,0.05
TYPE,2
REAL,2
E,NODE(1,0.05,0.05),NMAX+1
"""

SOLVE = """/SOLU
ANTYPE,STATIC
D,ROOT,ALL,0
D,NMAX+1,ALL,0
CMSEL,S,TIP
F,ALL,FZ,-100
ALLSEL
SOLVE
FINISH
"""


def test_archive_solves_like_the_deck_that_built_it(binary, tmp_path):
    built = tmp_path / "built"
    built.mkdir()
    deck = built / "cantilever.inp"
    deck.write_text(MODEL + "CDWRITE,DB,cantilever,cdb\nFINISH\n" + SOLVE)
    run([binary, "run", str(deck), "-o", str(built)])
    archive = built / "cantilever.cdb"
    assert archive.exists()
    again = tmp_path / "again"
    again.mkdir()
    (again / "cantilever.cdb").write_bytes(archive.read_bytes())
    reader = again / "from_archive.inp"
    reader.write_text("/PREP7\nCDREAD,DB,cantilever,cdb\n*GET,NMAX,NODE,0,NUM,MAX\n"
                      "NMAX=NMAX-1\nFINISH\n" + SOLVE)
    run([binary, "run", str(reader), "-o", str(again)])
    a = impactfe.open(str(built / "cantilever.h5")).field(["UX", "UY", "UZ"])
    b = impactfe.open(str(again / "from_archive.h5")).field(["UX", "UY", "UZ"])
    assert a.index.equals(b.index)
    for item in ("UX", "UY", "UZ"):
        assert np.array_equal(a[item].to_numpy(), b[item].to_numpy()), item  # bit for bit
    assert a["UZ"].min() < -1e-7  # the beam bends


def nblock_rows(text):
    """node -> (x, y, z) of the first NBLOCK of a CDB text (by its format's columns)."""
    lines = text.splitlines()
    k = next(i for i, line in enumerate(lines) if line.upper().startswith("NBLOCK"))
    widths = []
    for count, kind, width in re.findall(r"(\d*)([ieg])(\d+)", lines[k + 1].lower()):
        widths += [int(width)] * int(count or 1)
    rows = {}
    for line in lines[k + 2:]:
        if line.strip() == "-1" or line.upper().startswith("N,"):
            break
        cols, pos = [], 0
        for w in widths:
            cols.append(line[pos:pos + w].strip())
            pos += w
        rows[int(cols[0])] = tuple(float(c) if c else 0.0 for c in cols[3:6])
    return rows


def test_workbench_archive_nodes_read_as_written(binary, tmp_path):
    source = os.path.join(SHARED_CDB, "workbench_193.cdb")
    deck = tmp_path / "wb.inp"
    deck.write_text(f"/PREP7\nCDREAD,DB,'{source[:-4]}',cdb\nCDWRITE,DB,copy,cdb\nFINISH\n")
    run([binary, "run", str(deck), "-o", str(tmp_path)])
    original = nblock_rows(open(source).read())
    copied = nblock_rows((tmp_path / "copy.cdb").read_text())
    assert sorted(copied) == [219712, 219713, 219714]
    for node, xyz in original.items():
        assert copied[node] == xyz  # (1i7,2i9,6e21.13): numbers as written

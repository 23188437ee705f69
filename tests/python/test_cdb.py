"""CDB archives end to end: a model written by CDWRITE and read back by CDREAD solves to the same
bits as the deck that built it; public archives written by Workbench and HyperMesh
(../shared/cdb) read with their numbers as written."""
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


def test_hypermesh_archive_reads_its_shells(binary, tmp_path):
    """HyperMesh's archive: (3i8,6e16.9) nodes, (19i8) SHELL181 elements with its own column
    layout, an RLBLOCK shell thickness, MPDATA,R5.0 materials; its modal solution runs."""
    source = os.path.join(SHARED_CDB, "hypermesh.cdb")
    deck = tmp_path / "hm.inp"
    deck.write_text(f"/PREP7\nCDREAD,DB,'{source[:-4]}',cdb\n/PREP7\nCDWRITE,DB,copy,cdb\n"
                    "FINISH\n")
    run([binary, "run", str(deck), "-o", str(tmp_path)])
    text = (tmp_path / "copy.cdb").read_text()
    assert len(nblock_rows(text)) == 105
    lines = text[text.index("EBLOCK"):].splitlines()
    records = lines[2:lines.index(next(x for x in lines if x.strip() == "-1"))]
    assert len(records) == 80  # one line each: 4 nodes
    assert all(r.split()[1] == "1" and r.split()[8] == "4" for r in records)  # TYPE 1, 4 nodes
    assert "RLBLOCK,1,1,12,7" in text


def test_public_hexbeam_archive_bends_as_timoshenko(binary, tmp_path):
    """HexBeam.cdb (MAPDL 2019 R2): a 1 x 1 x 5 beam along Z of 40 SOLID186 bricks, E = 70 GPa,
    ν = 0.35, with its components. Clamped at z = 0 and loaded by P = 1000 in X spread over the
    nodes of the end z = 5, it bends at mid-length (z = 2.5, away from both ends' local effects)
    by Timoshenko's v = P z² (3L − z) / (6EI) + P z / (κGA), κ = 10(1 + ν)/(12 + 11ν)."""
    source = os.path.join(SHARED_CDB, "HexBeam.cdb")
    deck = tmp_path / "hexbeam.inp"
    deck.write_text(f"""/PREP7
CDREAD,DB,'{source[:-4]}',cdb
FINISH
/SOLU
ANTYPE,STATIC
NSEL,S,LOC,Z,0
D,ALL,ALL,0
NSEL,S,LOC,Z,5
*GET,NTIP,NODE,0,COUNT
F,ALL,FX,1000/NTIP
ALLSEL
SOLVE
FINISH
""")
    run([binary, "run", str(deck), "-o", str(tmp_path)])
    r = impactfe.open(str(tmp_path / "hexbeam.h5"))
    assert len(r.elements()) == 40 and set(r.elements()["type_name"]) == {"SOLID186"}
    nodes = r.nodes()
    mid = nodes.index[np.isclose(nodes["Z"], 2.5)]
    ux = r.field("UX").loc[mid, "UX"].mean()
    E, nu, P, L, z = 70e9, 0.35, 1000.0, 5.0, 2.5
    inertia, area = 1.0 / 12.0, 1.0
    kappa = 10 * (1 + nu) / (12 + 11 * nu)
    G = E / (2 * (1 + nu))
    expected = P * z**2 * (3 * L - z) / (6 * E * inertia) + P * z / (kappa * G * area)
    assert abs(ux / expected - 1) < 0.015, (ux, expected)

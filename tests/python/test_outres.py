"""OUTRES per item, frequency and component (issue 10): tests/decks/outres/outres_bar.inp writes
displacements every 5th substep, velocities of a node component every 10th, the element results
of an element component every 10th, reactions every 20th (and, in load step 2, stresses
of every element every 20th). Every history has exactly the times its item was written at, with
the values of the same run written with OUTRES,ALL,ALL; what was not written is an error in
`impactfe post` and in the package, not zeros; the file is smaller."""
import os
import re
import subprocess

import numpy as np
import pytest

import impactfe
from conftest import DECKS, run

DECK = os.path.join(DECKS, "outres", "outres_bar.inp")
H = 2.5e-6  # DELTIM of both load steps (100 substeps each)


def _times(substeps):
    """Times of substeps numbered over the whole run (load step 2 continues at 101)."""
    return np.array([k * H for k in substeps])


@pytest.fixture(scope="module")
def files(binary, tmp_path_factory):
    mixed = tmp_path_factory.mktemp("outres_mixed")
    run([binary, "run", DECK, "-o", str(mixed)])
    # The reference: the same deck writing everything at every substep.
    text = open(DECK).read()
    lines = [s for s in text.splitlines() if not s.startswith("OUTRES")]
    first_solve = lines.index("SOLVE")
    lines.insert(first_solve, "OUTRES,ALL,ALL")
    full = tmp_path_factory.mktemp("outres_full")
    deck = full / "outres_bar.inp"
    deck.write_text("\n".join(lines) + "\n")
    run([binary, "run", str(deck), "-o", str(full)])
    return str(mixed / "outres_bar.h5"), str(full / "outres_bar.h5")


def _same_at_common_times(mixed, full, expected_substeps, **query):
    got = mixed.history(**query).iloc[:, 0]
    ref = full.history(**query).iloc[:, 0]
    np.testing.assert_allclose(got.index.values, _times(expected_substeps), rtol=1e-12, atol=0)
    np.testing.assert_allclose(got.values, ref.loc[got.index].values, rtol=1e-12, atol=1e-300)


def test_each_item_has_the_times_it_was_written_at(files):
    mixed, full = (impactfe.open(f) for f in files)
    every5 = [0] + list(range(5, 201, 5))
    every10 = [0] + list(range(10, 201, 10))
    _same_at_common_times(mixed, full, every5, node=21, item="UX")
    _same_at_common_times(mixed, full, every5, node=8, item="UX")
    _same_at_common_times(mixed, full, every10, node=21, item="VX")  # TIP: nodes 15..21
    _same_at_common_times(mixed, full, [0] + list(range(20, 201, 20)), node=1, item="FX")
    # ROOT (elements 1..5): ESOL every 10th in both load steps; STRS (SAXL) every 10th in load
    # step 1, then every 20th for every element in load step 2 (OUTRES,STRS,20 replaces it).
    _same_at_common_times(mixed, full, every10, element=3, item="FORC")
    _same_at_common_times(mixed, full, every10, element=3, item="EPEL")
    _same_at_common_times(mixed, full, every10[:11] + list(range(120, 201, 20)), element=3,
                          item="SAXL")
    _same_at_common_times(mixed, full, list(range(120, 201, 20)), element=12, item="SAXL")
    # The full run stores every substep.
    assert len(full.history(node=21, item="UX")) == 201


def test_what_was_not_written_is_an_error(files, binary):
    mixed = impactfe.open(files[0])
    for query in (dict(node=5, item="VX"), dict(element=12, item="FORC"),
                  dict(element=12, item="EPEL"), dict(node=21, item="AX")):
        with pytest.raises(impactfe.ResultsError, match="no value is stored"):
            mixed.history(**query)
    p = subprocess.run([binary, "post", files[0], "--nsol", "5,VX"], capture_output=True,
                       text=True)
    assert p.returncode == 1 and "N5_VX: no value is stored" in p.stderr, p.stderr
    # Several columns: the union of their times, a column empty where it was not written.
    p = run([binary, "post", files[0], "--nsol", "21,VX", "--esol", "12,SAXL"])
    rows = [r.split(",") for r in p.stdout.splitlines()[1:]]
    assert len(rows) == 21  # VX at substeps 0, 10, ..., 200; SAXL at 120, 140, ..., 200
    assert all(r[1] for r in rows)
    assert sum(1 for r in rows if r[2]) == 5


def test_the_file_shrinks(files):
    mixed, full = (os.path.getsize(f) for f in files)
    assert mixed < 0.5 * full, (mixed, full)


def test_absent_rows_are_nan_in_the_file(files):
    h5py = pytest.importorskip("h5py")
    with h5py.File(files[0], "r") as f:
        a = f["analysis_1"]
        n = len(a["time"])
        v = a["V"][:n]
        ids = list(f["model/node_ids"][:])
        tip = [ids.index(k) for k in range(15, 22)]
        rest = [i for i in range(len(ids)) if i not in tip]
        assert np.isnan(v[:, rest, :]).all()
        written = np.isfinite(v[:, tip, 0]).all(axis=1)
        assert written.sum() == 21


def test_outres_stat_lists_the_settings(binary, tmp_path):
    text = open(DECK).read().replace("SOLVE\nTIME,5E-4", "OUTRES,STAT\nSOLVE\nTIME,5E-4")
    deck = tmp_path / "stat.inp"
    deck.write_text(text)
    p = run([binary, "run", str(deck), "-o", str(tmp_path)])
    assert re.search(r"NSOL\s+every 5 substeps and the last for all", p.stdout), p.stdout
    assert re.search(r"V\s+NONE for all; every 10 substeps and the last for component TIP",
                     p.stdout), p.stdout
    assert re.search(r"RSOL\s+every 20 substeps and the last for all", p.stdout), p.stdout

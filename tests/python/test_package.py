"""The Python package python/binary on the thesis results: the same numbers as `impactfe post`
(merge rule included), the energy table, modal results, format 1 files and a file read while the
job writes it."""
import os
import signal
import subprocess
import time

import numpy as np
import pytest

import impactfe
from conftest import DECKS, ROOT, post, run


def same_series(df, csv_column):
    """The package's column against the CSV of `impactfe post` (values printed with %.10e)."""
    a = df.iloc[:, 0].dropna()
    b = csv_column.dropna()
    assert len(a) == len(b) and len(a) > 0
    np.testing.assert_allclose(a.index.values, b.index.values, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(a.values, b.values, rtol=1e-9, atol=1e-12)


def test_crash1_histories_equal_post_with_the_merge_rule(binary, crash1):
    r = impactfe.open(crash1)
    csv = post(binary, crash1, "--nsol", "7,UX", "--nsol", "1,UX", "--esol", "6,SAXL",
               "--esol", "1,SAXL", "--gapf", "1", "--nsol", "7,VX")
    same_series(r.history(node=7, item="UX"), csv["N7_UX"])
    same_series(r.history(node=1, item="UX"), csv["N1_UX"])
    same_series(r.history(element=6, item="SAXL"), csv["E6_SAXL"])
    same_series(r.history(element=1, item="saxl"), csv["E1_SAXL"])
    same_series(r.history(gap=1), csv["GAP1"])
    same_series(r.history(node=7, item="VX"), csv["N7_VX"])
    # Reduced run then expansion: at t = 0.006 both analyses hold node 7; one row, the later one.
    assert list(r.analyses()["kind"]) == ["reduced_transient", "expansion"]
    ux = r.history(node=7, item="UX")
    assert ux.index.is_unique and ux.index.is_monotonic_increasing
    both = r.history(node=7, item=["UX", "VX"])
    assert list(both.columns) == ["N7_UX", "N7_VX"]


def test_helmet_histories_and_energy(binary, helmet):
    r = impactfe.open(helmet)
    csv = post(binary, helmet, "--nsol", "43,UZ", "--nsol", "43,AZ", "--esol", "1,SEQV_TOP",
               "--esol", "77,FORC", "--esol", "77,STAT", "--nsol", "1,FX")
    same_series(r.history(node=43, item="UZ"), csv["N43_UZ"])
    same_series(r.history(node=43, item="AZ"), csv["N43_AZ"])
    same_series(r.history(element=1, item="SEQV_TOP"), csv["E1_SEQV_TOP"])
    same_series(r.history(element=77, item="FORC"), csv["E77_FORC"])
    same_series(r.history(element=77, item="STAT"), csv["E77_STAT"])
    same_series(r.history(node=1, item="FX"), csv["N1_FX"])  # sparse reactions
    e = r.energy()
    assert list(e.columns[:6]) == ["analysis", "kinetic", "strain", "external_work", "gap_work",
                                   "dissipation"]
    assert e.index[0] == 0.0 and e.index.is_monotonic_increasing
    last = e.iloc[-1]
    # The run summary's line (impactfe run): numerical dissipation = what the terms leave over.
    np.testing.assert_allclose(last["numerical"],
                               last["external_work"] - last["kinetic"] - last["strain"]
                               - last["gap_work"] - last["dissipation"])
    assert last["numerical"] / last["external_work"] > 0.3  # Houbolt at the thesis step (44 %)


def test_modal_frequencies_and_shapes(binary, run_deck):
    res = run_deck(os.path.join(ROOT, "tests", "verification", "two_dof_chain_modes.inp"),
                   "modes")
    r = impactfe.open(res)
    f = r.frequencies()
    np.testing.assert_allclose(f["frequency_hz"].values, [3.110516370757561, 8.143437581206266],
                               rtol=1e-9)
    csv = run([binary, "post", res, "--freq"]).stdout.splitlines()
    assert [float(x.split(",")[1]) for x in csv[1:]] == pytest.approx(f["frequency_hz"].values,
                                                                      rel=1e-9)
    shape = r.mode_shape(1)
    assert list(shape.columns) == ["UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ"]
    mode_csv = run([binary, "post", res, "--mode", "1"]).stdout.splitlines()
    ux = {int(l.split(",")[0]): l.split(",")[1] for l in mode_csv[1:]}
    for node, value in ux.items():
        if value:
            assert shape.loc[node, "UX"] == pytest.approx(float(value), rel=1e-9, abs=1e-15)
    with pytest.raises(impactfe.ResultsError, match="mode 3 does not exist"):
        r.mode_shape(3)


def test_format_1_file(binary):
    v1 = os.path.join(DECKS, "files", "crash1_format_v1.h5")
    r = impactfe.open(v1)
    assert r.format_version == 1
    csv = post(binary, v1, "--nsol", "7,UX", "--esol", "6,SAXL", "--gapf", "1")
    same_series(r.history(node=7, item="UX"), csv["N7_UX"])
    same_series(r.history(element=6, item="SAXL"), csv["E6_SAXL"])


def test_errors_are_clear(crash1):
    r = impactfe.open(crash1)
    with pytest.raises(impactfe.ResultsError, match="node 999 is not in results file"):
        r.history(node=999, item="UX")
    with pytest.raises(impactfe.ResultsError, match="unknown nodal result label 'UQ'"):
        r.history(node=7, item="UQ")
    with pytest.raises(impactfe.ResultsError, match="not stored for element 6"):
        r.history(element=6, item="SEQV")
    with pytest.raises(impactfe.ResultsError, match="no modal results"):
        r.frequencies()


def test_read_while_the_job_writes(binary, tmp_path):
    """h5py opens the file of a running job (locking=False, docs/results_file.md); the points
    it sees, some of them still in the staging datasets, equal the finished file's. The job
    stores a point every 1200 substeps, so that its time blocks take several times the writer's
    0.1-s sync, which leaves the points of a partial block in staging."""
    deck = os.path.join(os.path.dirname(__file__), "decks", "slow_chain.inp")
    job = subprocess.Popen([binary, "run", deck, "-o", str(tmp_path)],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    path = tmp_path / "slow_chain.h5"
    seen = None
    try:
        deadline = time.time() + 120
        while time.time() < deadline and job.poll() is None:
            time.sleep(0.05)
            if not path.exists():
                continue
            try:
                job.send_signal(signal.SIGSTOP)  # between two reads the file must not move
                r = impactfe.open(path)
                a = r._analyses[0] if r._analyses else None
                if a is not None and 64 < len(a.times) and a.first_recent < len(a.times):
                    seen = r.history(node=61, item="UX")
                r.close()
            except (OSError, KeyError, impactfe.ResultsError):
                pass  # caught between two writes: try again
            finally:
                job.send_signal(signal.SIGCONT)
            if seen is not None:
                break
    finally:
        rc = job.wait(timeout=300)
    assert rc == 0
    assert seen is not None, "never saw the job half-way with points in staging"
    final = impactfe.open(path).history(node=61, item="UX")
    np.testing.assert_array_equal(seen.values[:, 0], final.loc[seen.index].values[:, 0])
    assert len(final) == 201

"""Results.energy (docs/python.md, "Energy"): the kinetic energy of the initial velocities (IC)
is energy put in, so the numerical term starts at 0 and ends at the run summary's "numerical
dissipation"; a run continued from a restart point carries the T0 of the run it continues."""
import os
import re
import shutil

import h5py
import numpy as np
import pytest

import impactfe
from conftest import DECKS, run

MODEL = os.path.join(DECKS, "restart", "two_mass_model.inp")
LOAD_STEP_1 = "ACEL,0,386.4,0\nTIME,0.006\nSOLVE\n"
LOAD_STEP_2 = "ACEL,0,200,0\nTIME,0.012\nSOLVE\n"


def summary_numerical(log):
    """The last 'numerical dissipation' of the run summary in a job's log."""
    with open(log) as f:
        values = re.findall(r"numerical dissipation (\S+?)(?:,|\n|$)", f.read())
    assert values, f"no energy line in {log}"
    return float(values[-1])


def test_plate_drop_initial_kinetic_energy_is_put_in(plate_drop):
    r = impactfe.open(plate_drop)
    e = r.energy()
    # m v^2 / 2 of the plate (rho a^2 t, 5 m/s), independently of the file's kinetic column.
    t0 = 0.5 * 7850 * 0.5 * 0.5 * 0.005 * 5.0**2
    assert t0 == pytest.approx(122.65625)
    np.testing.assert_allclose(e["initial_kinetic"], t0, rtol=1e-12)
    first, last = e.iloc[0], e.iloc[-1]
    assert e.index[0] == 0.0 and first["kinetic"] == pytest.approx(t0, rel=1e-12)
    assert abs(first["numerical"]) <= 1e-12 * t0  # was -T0 = -122.66
    # What stays in the plate or went to the contact, as the summary counts it.
    log = os.path.splitext(plate_drop)[0] + ".log"
    assert last["numerical"] == pytest.approx(summary_numerical(log), rel=1e-5, abs=1e-6 * t0)
    # The default integrator damps the Mindlin plate's transverse-shear modes that the slaps
    # excite: 10.9 J (8.9 %) at this step, 7.5 J at half of it; the run warns about it.
    assert 0 < last["numerical"] < 0.10 * t0
    assert last["strain"] > 0.2 * t0  # the slap bent the plate


def test_no_initial_velocity_no_initial_kinetic(helmet):
    e = impactfe.open(helmet).energy()
    assert (e["initial_kinetic"] == 0.0).all()
    last = e.iloc[-1]
    np.testing.assert_allclose(last["numerical"],
                               last["external_work"] - last["kinetic"] - last["strain"]
                               - last["gap_work"] - last["dissipation"])


def _deck(directory, name, body):
    path = directory / f"{name}.inp"
    path.write_text(f"/FILNAME,run\n/INPUT,{MODEL}\n{body}FINISH\n")
    return str(path)


def test_a_continued_run_carries_the_initial_kinetic_energy(binary, tmp_path):
    """two_mass_model.inp starts both masses at 40 in/s (IC): T0 = 1600. Stopped after load
    step 1 and continued (a second analysis without an initial state): the same energy table
    as the uninterrupted run, numerical term included."""
    whole, split = tmp_path / "whole", tmp_path / "split"
    whole.mkdir()
    split.mkdir()
    run([binary, "run", _deck(whole, "whole", LOAD_STEP_1 + LOAD_STEP_2), "-o", str(whole)])
    run([binary, "run", _deck(split, "first", "RESCONTROL,DEFINE,ALL,LAST\n" + LOAD_STEP_1),
         "-o", str(split)])
    run([binary, "run", _deck(split, "second", "ANTYPE,TRANS,RESTART\n" + LOAD_STEP_2),
         "-o", str(split)])
    a = impactfe.open(whole / "run.h5").energy()
    b = impactfe.open(split / "run.h5").energy()
    assert list(b["analysis"].unique()) == [1, 2]
    np.testing.assert_allclose(b.index, a.index, rtol=1e-12)
    np.testing.assert_allclose(b["initial_kinetic"], 1600.0, rtol=1e-12)
    for column in ("kinetic", "gap_work", "numerical"):
        np.testing.assert_allclose(b[column], a[column], rtol=1e-9, atol=1e-9 * 1600)
    assert b["numerical"].iloc[-1] == pytest.approx(summary_numerical(split / "second.log"),
                                                    rel=1e-5)
    # The continued analysis alone (the file of the run it continues is gone): T0 unknown.
    alone = tmp_path / "alone.h5"
    shutil.copy(split / "run.h5", alone)
    with h5py.File(alone, "r+") as f:
        del f["analysis_1"]
        f.move("analysis_2", "analysis_1")
    e = impactfe.open(alone).energy()
    assert e["initial_kinetic"].isna().all() and e["numerical"].isna().all()
    assert e["kinetic"].notna().all()

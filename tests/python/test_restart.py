"""Restart (issue 16; docs/solution_control.md): a transient stopped at a restart point and
continued in a new process (ANTYPE,,RESTART) equals the uninterrupted run to round-off.

The model (tests/decks/restart/two_mass_model.inp) has two contacts that close and reopen, so
the continued run needs the element statuses, the integrator history (Houbolt keeps two past
displacements) and the load ramp (KBC,0) of the point. Runs: the uninterrupted two-load-step
run; the run stopped after load step 1 and continued; and a continuation from a point inside
load step 2 (RESCONTROL every 20 substeps). The continued run adds an analysis to the results
file, whose merged histories (`impactfe post`) are compared."""
import os

import numpy as np
import pytest

from conftest import DECKS, post, run

MODEL = os.path.join(DECKS, "restart", "two_mass_model.inp")
LOAD_STEP_1 = "ACEL,0,386.4,0\nTIME,0.006\nSOLVE\n"
LOAD_STEP_2 = "ACEL,0,200,0\nTIME,0.012\nSOLVE\n"


def _deck(directory, name, scheme, body):
    path = directory / f"{name}.inp"
    trnopt = "TRNOPT,FULL,,,,,HOUB\n" if scheme == "houbolt" else ""
    path.write_text(f"/FILNAME,run\n/INPUT,{MODEL}\n{trnopt}{body}FINISH\n")
    return str(path)


def _histories(binary, h5):
    return {f"{n}{i}": post(binary, h5, "--nsol", f"{n},{i}").iloc[:, 0]
            for n in (2, 3) for i in ("UY", "VY", "AY")}


@pytest.mark.parametrize("scheme", ["newmark", "houbolt"])
def test_stopped_and_continued_equals_uninterrupted(binary, tmp_path, scheme):
    whole = tmp_path / "whole"
    whole.mkdir()
    run([binary, "run", _deck(whole, "whole", scheme,
                              "RESCONTROL,DEFINE,ALL,20\n" + LOAD_STEP_1 + LOAD_STEP_2),
         "-o", str(whole)])
    reference = _histories(binary, str(whole / "run.h5"))

    # Stopped at the end of load step 1, continued in a new process.
    split = tmp_path / "split"
    split.mkdir()
    run([binary, "run", _deck(split, "first", scheme, "RESCONTROL,DEFINE,ALL,LAST\n" + LOAD_STEP_1),
         "-o", str(split)])
    assert os.path.exists(split / "run.rst.h5")
    p = run([binary, "run", _deck(split, "second", scheme, "ANTYPE,TRANS,RESTART\n" + LOAD_STEP_2),
             "-o", str(split)])
    assert "continued from the restart point of load step 1 substep 60" in p.stdout
    # From inside load step 2 (substep 20 of 60), into the uninterrupted run's own file.
    p = run([binary, "run", _deck(whole, "inside", scheme, "ANTYPE,TRANS,RESTART,2,20\n" +
                                  LOAD_STEP_2), "-o", str(whole)])
    assert "continued from the restart point of load step 2 substep 20" in p.stdout

    for directory in (split, whole):
        got = _histories(binary, str(directory / "run.h5"))
        for name, ref in reference.items():
            g = got[name]
            np.testing.assert_allclose(g.index.values, ref.index.values, rtol=1e-12, atol=1e-15)
            scale = max(1.0, np.max(np.abs(ref.values)))
            np.testing.assert_allclose(g.values, ref.values, rtol=0, atol=1e-12 * scale,
                                       err_msg=f"{directory.name} {name}")


def test_restart_point_that_does_not_exist(binary, tmp_path):
    run([binary, "run", _deck(tmp_path, "first", "newmark",
                              "RESCONTROL,DEFINE,ALL,LAST\n" + LOAD_STEP_1), "-o", str(tmp_path)])
    p = run([binary, "run", _deck(tmp_path, "second", "newmark",
                                  "ANTYPE,TRANS,RESTART,3\n" + LOAD_STEP_2), "-o", str(tmp_path)],
            expect=1)
    assert "no restart point at load step 3" in p.stderr and "1,60" in p.stderr

"""Restart of runs whose elements carry a committed state, and restart inside an AUTOTS load step
(issue 16; docs/solution_control.md "Restart").

Each case runs the deck uninterrupted with restart points (RESCONTROL), then continues it in a
new process (ANTYPE,,RESTART) from the end of load step 1 and from a point inside load step 2,
and compares the merged histories (`impactfe post`) with the uninterrupted run: same times, same
values to round-off (1e-12 of the largest value). The continued run needs what the elements have
committed at the point, not only the displacements:
- a plastic bar (LINK180 / BEAM188 with BISO, SOLID185 / PLANE182 with BKIN) striking a wall
  through a COMBIN40 gap: plastic strain, back stress, equivalent plastic strain per point or
  fibre;
- Coulomb friction through a COMBIN40 slider (tests/verification/coulomb_friction.inp): the
  slip of the slider and its sliding direction;
- a brick sliding down a rigid incline on CONTA175 contact with friction: the stick anchor,
  the sliding distance and the status of each contact point;
- two masses landing through gaps with AUTOTS (tests/decks/autots/two_mass_impact.inp): the step
  controller's time, step, growth streak and ceiling, continued inside the load step with the
  same substep history.
SAVE / /CLEAR / RESUME of AUTOTS, the DELTIM limits and RESCONTROL gives the same run too."""
import os
import re

import numpy as np
import pytest

from conftest import DECKS, post, run

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def _bar_model(family):
    """A bar (L = 10, A = 1, rho = 1, E = 1e4, sigma_y = 100, Et = 1000) of 10 elements moving
    at v0 = 2 toward a wall 0.01 away (COMBIN40 K1 = 1e5): the impact stress rho c v0 = 200
    yields the bar from the struck end (tests/unit/test_plastic_beams.cpp)."""
    d = ["/PREP7"]
    if family == "LINK180":
        d += ["ET,1,LINK180", "SECTYPE,1,LINK", "SECDATA,1.0"]
    elif family == "BEAM188":
        d += ["ET,1,BEAM188", "SECTYPE,1,BEAM,RECT", "SECDATA,1,1,1,1"]
    elif family == "PLANE182":
        d += ["ET,1,PLANE182"]  # plane stress, thickness 1
    else:
        d += ["ET,1,SOLID185"]
    tb = "TB,BKIN,1" if family in ("SOLID185", "PLANE182") else "TB,BISO,1"
    d += ["ET,2,COMBIN40,,,1", "MP,EX,1,1E4", "MP,PRXY,1,0.3", "MP,DENS,1,1.0", tb,
          "TBDATA,1,100,1000"]
    if family == "SOLID185":
        corners = [(0, 0), (1, 0), (1, 1), (0, 1)]
        for i in range(11):
            for j, (y, z) in enumerate(corners):
                d.append(f"N,{4 * i + j + 1},{i},{y},{z}")
        d += ["TYPE,1"] + [f"E,{','.join(str(4 * i + j + 1) for j in range(8))}"
                           for i in range(10)]
        d += [f"N,{100 + j},11,{y},{z}" for j, (y, z) in enumerate(corners)]
        d += ["R,2,2.5E4,,,0.01", "TYPE,2", "REAL,2"] + [f"E,{41 + j},{100 + j}" for j in range(4)]
        moving, tip = range(1, 45), 41
        ground = "D,100,ALL,,,103"
    elif family == "PLANE182":
        for i in range(11):
            d += [f"N,{2 * i + 1},{i},0", f"N,{2 * i + 2},{i},1"]
        d += ["TYPE,1"] + [f"E,{2 * i + 1},{2 * i + 3},{2 * i + 4},{2 * i + 2}" for i in range(10)]
        d += ["N,100,11,0", "N,101,11,1", "R,2,5E4,,,0.01", "TYPE,2", "REAL,2", "E,21,100",
              "E,22,101"]
        moving, tip = range(1, 23), 21
        ground = "D,100,ALL,,,101"
    else:
        d += [f"N,{i + 1},{i}" for i in range(11)] + ["N,20,11", "TYPE,1"]
        d += [f"E,{i},{i + 1}" for i in range(1, 11)]
        d += ["R,2,1E5,,,0.01", "TYPE,2", "REAL,2", "E,11,20"]
        moving, tip = range(1, 12), 11
        ground = "D,20,ALL"
    d += ["FINISH", "/SOLU", "ANTYPE,TRANS", "TRNOPT,FULL", "TINTP,,0.25,0.5", "LUMPM,ON",
          "D,ALL,UY"] + (["D,ALL,UZ"] if family != "PLANE182" else []) + [ground]
    if family == "BEAM188":
        d += ["D,ALL,ROTX", "D,ALL,ROTY", "D,ALL,ROTZ"]
    d += [f"IC,{n},UX,0,2.0" for n in moving]
    d += ["DELTIM,5E-4", "OUTRES,ALL,ALL"]
    return "\n".join(d) + "\n", tip


FRICTION_LS1 = "TIMINT,OFF\nKBC,1\nF,2,FX,105\nTIME,1.0E-6\nNSUBST,1\nSOLVE\n"
FRICTION_LS2 = "TIMINT,ON\nFDELE,2,FX\nTIME,1.0\nDELTIM,5.0E-4\nOUTRES,ALL,ALL\nSOLVE\n"


def _friction_model():
    """tests/verification/coulomb_friction.inp up to its load steps."""
    with open(os.path.join(ROOT, "tests", "verification", "coulomb_friction.inp")) as f:
        text = f.read()
    return text[:text.index("KBC,1")]


def _write(directory, name, text):
    path = directory / name
    path.write_text(text)
    return str(path)


def _histories(binary, h5, nodal, elemental):
    requests = [a for n in nodal for a in ("--nsol", n)]
    requests += [a for e in elemental for a in ("--esol", e)]
    return post(binary, h5, *requests)


def _compare(got, ref, what):
    np.testing.assert_allclose(got.index.values, ref.index.values, rtol=1e-12, atol=1e-15,
                               err_msg=f"{what}: times")
    worst = 0.0
    for column in ref.columns:
        scale = max(1.0, float(np.max(np.abs(ref[column].values))))
        worst = max(worst, float(np.max(np.abs(got[column].values - ref[column].values))) / scale)
        np.testing.assert_allclose(got[column].values, ref[column].values, rtol=0,
                                   atol=1e-12 * scale, err_msg=f"{what} {column}")
    print(f"{what}: {len(ref)} times, largest difference {worst:.3g} of the largest value")


def _stopped_and_continued(binary, tmp_path, model, ls1, ls2, every, inside, nodal, elemental):
    """The uninterrupted run (RESCONTROL,DEFINE,ALL,every), the run stopped after load step 1 and
    continued, and a continuation from load step 2 substep `inside`; returns the reference
    histories after checking that both continued runs equal them."""
    model_path = _write(tmp_path, "model.inp", model)
    whole = tmp_path / "whole"
    split = tmp_path / "split"
    whole.mkdir()
    split.mkdir()

    def deck(directory, name, body):
        return _write(directory, f"{name}.inp", f"/FILNAME,run\n/INPUT,{model_path}\n{body}FINISH\n")

    p = run([binary, "run", deck(whole, "whole", f"RESCONTROL,DEFINE,ALL,{every}\n" + ls1 + ls2),
             "-o", str(whole)])
    reference = _histories(binary, str(whole / "run.h5"), nodal, elemental)
    run([binary, "run", deck(split, "first", "RESCONTROL,DEFINE,ALL,LAST\n" + ls1),
         "-o", str(split)])
    p = run([binary, "run", deck(split, "second", "ANTYPE,TRANS,RESTART\n" + ls2),
             "-o", str(split)])
    assert "continued from the restart point of load step 1" in p.stdout
    p = run([binary, "run", deck(whole, "inside", f"ANTYPE,TRANS,RESTART,2,{inside}\n" + ls2),
             "-o", str(whole)])
    assert f"continued from the restart point of load step 2 substep {inside}" in p.stdout
    for directory in (split, whole):
        _compare(_histories(binary, str(directory / "run.h5"), nodal, elemental), reference,
                 directory.name)
    return reference


@pytest.mark.parametrize("family", ["LINK180", "BEAM188", "SOLID185", "PLANE182"])
def test_plastic_bar_restarted_equals_uninterrupted(binary, tmp_path, family):
    model, tip = _bar_model(family)
    ls1 = "TIME,0.02\nSOLVE\n"
    ls2 = "TIME,0.06\nSOLVE\n"
    ref = _stopped_and_continued(binary, tmp_path, model, ls1, ls2, 20, 20,
                                 [f"{tip},UX", f"{tip},VX", "1,UX", "1,VX"],
                                 ["10,EPEQ", "9,EPEQ", "10,SRAT"])
    # The bar has yielded by the end of load step 1 (the restart points carry plastic history).
    assert ref.loc[ref.index <= 0.02 + 1e-12, "E10_EPEQ"].max() > 1e-4


def test_slider_restarted_equals_uninterrupted(binary, tmp_path):
    ref = _stopped_and_continued(binary, tmp_path, _friction_model(), FRICTION_LS1, FRICTION_LS2,
                                 500, 500, ["2,UX", "2,VX"], ["2,SLIDE", "2,STAT"])
    # The slider slips in the static step (slide 0.9995 = x0 - FSLIDE/K1) and is sliding back
    # at the restart point inside load step 2 (t = 0.25): its slip is part of the state.
    slide = ref["E2_SLIDE"].values
    assert abs(slide[1] - 0.9995) < 1e-9
    at = np.argmin(np.abs(ref.index.values - 0.25))
    assert ref["E2_STAT"].values[at] == ref["E2_STAT"].values[1]  # sliding, as in load step 1
    assert slide[at] < -0.5 and abs(slide[at] - slide[at - 1]) > 1e-4


def _incline_model():
    """tests/verification/conta175_incline_slide.inp (a brick on four CONTA175 nodes sliding down
    a rigid plane inclined at 40 deg, MU = 0.5) up to its load steps, and its two load steps with
    the slide shortened to t = 0.301."""
    with open(os.path.join(ROOT, "tests", "verification", "conta175_incline_slide.inp")) as f:
        text = f.read()
    cut = text.index("KBC,1")
    steps = text[cut:text.index("FINISH", cut)].replace("TIME,1.001", "TIME,0.301")
    split = steps.index("TIMINT,ON")
    # KBC,1 again in load step 2: a deck that continues in a new process starts from the default
    # KBC,0, and the down-slope ACEL is a step change.
    return text[:cut], steps[:split], "KBC,1\n" + steps[split:]


def test_frictional_contact_restarted_equals_uninterrupted(binary, tmp_path):
    """Surface contact with Coulomb friction (CONTA175 on a rigid target): the contact elements'
    committed state (stick anchor, sliding distance, status) is part of the restart point. The
    block sticks in load step 1 and slides in load step 2; continued from t = 0.2."""
    model, ls1, ls2 = _incline_model()
    ref = _stopped_and_continued(binary, tmp_path, model, ls1, ls2, 100, 200,
                                 ["1,UX", "1,VX", "5,UX"],
                                 ["4,SLIDE", "4,STAT", "4,FT", "6,SLIDE", "6,FN"])
    at = np.argmin(np.abs(ref.index.values - 0.2))
    assert ref["E4_STAT"].values[at] == 2  # sliding at the restart point
    assert ref["E4_SLIDE"].values[at] > 0.01  # ... with a sliding distance to carry on


def _autots_model(scheme):
    with open(os.path.join(DECKS, "autots", "two_mass_impact.inp")) as f:
        text = f.read()
    text = text.replace("/FILNAME,two_mass_impact\n", "")
    if scheme == "houbolt":
        text = text.replace("TRNOPT,FULL\n", "TRNOPT,FULL,,,,,HOUB\n")
    return text[:text.index("TIME,0.012")]


def _substeps(log):
    with open(log) as f:
        text = f.read()
    m = re.search(r"automatic time stepping, load step 1: .*", text)
    assert m, text
    return m.group(0)


@pytest.mark.parametrize("scheme", ["newmark", "houbolt"])
def test_restart_inside_an_autots_load_step(binary, tmp_path, scheme):
    """Load step 1 to t = 0.004 (gap 1 closes at 0.002), load step 2 to 0.012 (gap 2 closes, both
    reopen), both with AUTOTS; restart points every 2nd substep; continued from substep 2 of
    load step 2, while a gap is closed, with a cut (substep 3) and steps under the contact
    ceiling still to come."""
    model = _autots_model(scheme)
    nodal = [f"{n},{i}" for n in (2, 3) for i in ("UY", "VY", "AY")]
    ref = _stopped_and_continued(binary, tmp_path, model, "TIME,0.004\nSOLVE\n",
                                 "TIME,0.012\nSOLVE\n", 2, 2, nodal, ["1,STAT", "2,STAT"])
    t = ref.index.values
    dt = np.diff(t[t > 0.004 - 1e-12])
    assert dt.max() < 0.5 * 0.004  # load step 2 was cut below its first step 0.004
    assert len(np.unique(np.round(dt, 12))) > 2  # ... and its steps changed


def test_autots_constant_step_mismatch_is_refused(binary, tmp_path):
    """A point inside an AUTOTS load step continued with constant steps: InputError."""
    model_path = _write(tmp_path, "model.inp", _autots_model("newmark"))
    run([binary, "run", _write(tmp_path, "a.inp", f"/FILNAME,run\n/INPUT,{model_path}\n"
                               "RESCONTROL,DEFINE,ALL,5\nTIME,0.012\nSOLVE\nFINISH\n"),
         "-o", str(tmp_path)])
    p = run([binary, "run", _write(tmp_path, "b.inp", f"/FILNAME,run\n/INPUT,{model_path}\n"
                                   "ANTYPE,TRANS,RESTART,1,5\nAUTOTS,OFF\nTIME,0.012\nSOLVE\n"
                                   "FINISH\n"), "-o", str(tmp_path)], expect=1)
    assert "continue it with AUTOTS,ON" in p.stderr


def test_save_clear_resume_keeps_autots_and_rescontrol(binary, tmp_path):
    """AUTOTS,ON + DELTIM limits + RESCONTROL set, SAVE, /CLEAR, RESUME, SOLVE: the same substep
    history as the deck without the save / resume, and the same restart points."""
    model = _autots_model("newmark") + "RESCONTROL,DEFINE,ALL,5\nTIME,0.012\n"
    direct = tmp_path / "direct"
    resumed = tmp_path / "resumed"
    direct.mkdir()
    resumed.mkdir()
    run([binary, "run", _write(direct, "d.inp", "/FILNAME,run\n" + model + "SOLVE\nFINISH\n"),
         "-o", str(direct)])
    run([binary, "run", _write(resumed, "r.inp", "/FILNAME,run\n" + model +
                               "SAVE,kept,db\n/CLEAR\nRESUME,kept,db\n/SOLU\n"
                               "RESCONTROL,STATUS\nSOLVE\nFINISH\n"), "-o", str(resumed)])
    with open(resumed / "r.log") as f:
        assert "RESCONTROL: restart points at load steps every 1 and substeps every 5" in f.read()
    # The same substeps and cuts (the summary line of the load step).
    assert _substeps(resumed / "r.log") == _substeps(direct / "d.log")
    assert re.search(r" [1-9][0-9]* cuts", _substeps(direct / "d.log"))  # AUTOTS cut steps
    nodal = [f"{n},{i}" for n in (2, 3) for i in ("UY", "VY")]
    _compare(_histories(binary, str(resumed / "run.h5"), nodal, []),
             _histories(binary, str(direct / "run.h5"), nodal, []), "resumed")
    assert os.path.exists(resumed / "run.rst.h5")

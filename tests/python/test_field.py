"""Results.field (docs/python.md, "Fields"): one quantity over every node or element at one stored
point. Every value equals the history of its node / element at that time (and so `impactfe
post`), the merge rule included; the time selection never interpolates; the model columns
(coordinates, centroids, parts) come from the model; the plate drop's total contact force from
the CONTA174 faces balances the rigid floor's pilot reaction."""
import os
import shutil

import h5py
import numpy as np
import pytest

import impactfe
from conftest import DECKS, post


def test_helmet_nodal_field_equals_histories_and_post(binary, helmet):
    r = impactfe.open(helmet)
    t = r.history(element=77, item="STAT").query("E77_STAT == 1").index[0]  # a stored time
    f = r.field(["UZ", "VZ", "AZ"], time=t)
    assert list(f.columns) == ["X", "Y", "Z", "part", "UZ", "VZ", "AZ"]
    assert f.index.name == "node" and list(f.index) == list(r.node_ids)
    np.testing.assert_array_equal(f[["X", "Y", "Z"]].to_numpy(), r.node_coordinates)
    for node in r.node_ids:
        h = r.history(node=int(node), item=["UZ", "VZ", "AZ"])
        np.testing.assert_array_equal(f.loc[node, ["UZ", "VZ", "AZ"]].to_numpy(float),
                                      h.loc[t].to_numpy(float))
    csv = post(binary, helmet, "--nsol", "43,UZ", "--nsol", "1,UZ")
    row = csv.iloc[np.argmin(np.abs(csv.index.to_numpy() - t))]  # times printed with %.10e
    assert row.name == pytest.approx(t, rel=1e-10)
    assert f.loc[43, "UZ"] == pytest.approx(row["N43_UZ"], rel=1e-9)
    assert f.loc[1, "UZ"] == pytest.approx(row["N1_UZ"], rel=1e-9)
    assert f.attrs["time"] == t and f.attrs["set"] == r.sets().query("time == @t").index[0]


def test_helmet_element_fields_as_stored(helmet):
    r = impactfe.open(helmet)
    t = 0.06
    shells = r.field("SEQV_TOP", time=t)
    assert set(shells["type_name"]) == {"SHELL63"} and len(shells) == 72
    assert list(shells.columns) == ["X", "Y", "Z", "part", "type_name", "type", "mat", "real",
                                    "SEQV_TOP"]
    for e in (1, 40, 72):
        assert shells.loc[e, "SEQV_TOP"] == r.history(element=e, item="SEQV_TOP").loc[t].iloc[0]
    # An item of two families (shells and bricks): every element that has it.
    epeq = r.field("EPEQ", time=t)
    assert set(epeq["type_name"]) == {"SHELL63", "SOLID45"} and len(epeq) == 76
    gaps = r.field(["FORC", "STAT"], time=t)
    assert list(gaps.index) == list(range(77, 87))
    assert set(gaps["part"]) == {"COMBIN40 type 3 mat 2 real 2", "COMBIN40 type 3 mat 2 real 3"}
    # Centroid of brick 73 from its 8 nodes.
    row = list(r.element_ids).index(73)
    nodes = [n for n in r._model.element_nodes[row] if n]
    expect = r.nodes().loc[nodes, ["X", "Y", "Z"]].mean().to_numpy()
    np.testing.assert_allclose(r.field("SEQV", time=t).loc[73, ["X", "Y", "Z"]].to_numpy(float),
                               expect)


def test_time_selection_is_exact_and_never_interpolated(helmet):
    r = impactfe.open(helmet)
    at = r.field("UZ", time=0.04)
    assert r.field("UZ", time=0.04 * (1 + 1e-12)).equals(at)  # the round-off of a typed time
    with pytest.raises(impactfe.ResultsError, match=r"time 0\.0405 is not a stored time point "
                       r"\(no interpolation\): the nearest stored times are 0\.04 and 0\.044; "
                       r"stored: 191 time points from 0 to 0\.08"):
        r.field("UZ", time=0.0405)
    with pytest.raises(impactfe.ResultsError, match="nearest stored time is 0.08;"):
        r.field("UZ", time=1.0)
    # t = 0: the initial state, not a POST1 set.
    zero = r.field("UZ", time=0)
    assert zero["UZ"].abs().max() == 0.0 and zero.attrs["set"] is None
    # set= numbers are POST1's (the initial state is not one); neither = the last set.
    sets = r.sets()
    assert len(sets) == 190 and sets.loc[10, "time"] == pytest.approx(0.04)
    assert r.field("UZ", set=10).equals(at)
    last = r.field("UZ")
    assert last.attrs["set"] == 190 and last.equals(r.field("UZ", time=0.08))
    assert r.field("UZ", analysis=1).equals(last)


def test_reduced_run_and_expansion_merge_as_histories(crash1):
    r = impactfe.open(crash1)
    merged = r.field("UX", time=0.006)
    assert merged.attrs["point"].endswith("analysis 1+2)")
    for node in (1, 2, 7):
        h = r.history(node=node, item="UX")
        assert merged.loc[node, "UX"] == h.loc[0.006].iloc[0]
    # The reduced run alone (its slave displacements are recovered at every step) and the
    # expansion alone give the same displacements; node 10 (the gap's ground) has no DOF.
    for k in (1, 2):
        alone = r.field("UX", time=0.006, analysis=k)
        assert alone.attrs["point"].endswith(f"analysis {k})")
        np.testing.assert_allclose(alone["UX"].to_numpy(), merged["UX"].to_numpy(), rtol=1e-9)
    assert np.isnan(merged.loc[10, "UX"]) and merged.loc[10, "part"] == ""
    # Sets: the expansion's points only (MAPDL's file holds the expanded solutions).
    assert set(r.sets()["kind"]) == {"expansion"}
    saxl = r.field("SAXL", time=0.006)
    assert list(saxl.index) == [1, 2, 3, 4, 5, 6]
    assert saxl.loc[6, "SAXL"] == r.history(element=6, item="SAXL").loc[0.006].iloc[0]
    with pytest.raises(impactfe.ResultsError, match=r"SAXL has no value at .*analysis 1\) .*"
                       r"stored in analyses \[2\]"):
        r.field("SAXL", time=0.006, analysis=1)


def test_plate_drop_contact_force_balances_the_pilot_reaction(plate_drop):
    """Σ FN of the CONTA174 faces (each face's total normal force) along the floor's normal
    n = (0, 0.05, 1)/|.| equals the reaction at the rigid floor's pilot node."""
    r = impactfe.open(plate_drop)
    n = np.array([0.0, 0.05, 1.0]) / np.hypot(0.05, 1.0)
    pilot = int(r.node_ids.max()) - 4  # the deck's NMAX+1
    checked = 0
    for t in (0.0005, 0.001, 0.0016, 0.0028, 0.004):  # 0.0005 before the first slap
        fn = r.field("FN", time=t)
        assert set(fn["type_name"]) == {"CONTA174"} and len(fn) == 100
        reaction = r.field(["FX", "FY", "FZ"], time=t)
        assert pilot in reaction.index
        total = fn["FN"].sum()
        np.testing.assert_allclose(reaction.loc[pilot, ["FX", "FY", "FZ"]].to_numpy(float),
                                   total * n, rtol=1e-9, atol=1e-9 * max(total, 1.0))
        checked += total > 1000.0
    assert checked >= 2  # the contact carried load at some of these times
    # The shells' parts are the shells', not the CONTA174 faces on the same nodes.
    nodes = r.nodes()
    assert set(nodes.loc[nodes.index < pilot, "part"]) == {"SHELL181 type 1 mat 1 real 1"}
    seqv = r.field("SEQV_TOP", time=0.003)
    assert len(seqv) == 100 and seqv["SEQV_TOP"].max() > 1e8  # bent by the slap (Pa)


def test_modal_sets_are_mode_shapes(plate_modes):
    r = impactfe.open(plate_modes)
    sets = r.sets()
    assert list(sets["mode"]) == [1, 2, 3, 4] and sets["time"].isna().all()
    np.testing.assert_array_equal(sets["frequency_hz"], r.frequencies()["frequency_hz"])
    first = r.field("UZ", set=1)
    np.testing.assert_array_equal(first["UZ"].to_numpy(), r.mode_shape(1)["UZ"].to_numpy())
    assert first.attrs["time"] == pytest.approx(r.frequencies().loc[1, "frequency_hz"])
    centre = first["UZ"].abs().idxmax()
    assert first.loc[centre, ["X", "Y"]].tolist() == pytest.approx([0.25, 0.25])
    assert r.field("UZ").attrs["set"] == 4  # the last set: the last mode
    with pytest.raises(impactfe.ResultsError, match="holds mode shapes only .* not VX"):
        r.field("VX", set=1)
    with pytest.raises(impactfe.ResultsError, match="stores no time point; modes are selected"):
        r.field("UZ", time=0.0)


def test_items_not_written_by_outres_are_errors(run_deck):
    r = impactfe.open(run_deck(os.path.join(DECKS, "outres", "outres_bar.inp"), "outres"))
    h = 2.5e-6
    u = r.field("UX", time=5 * h)  # displacements every 5th substep
    assert np.isfinite(u["UX"]).all() and len(u) == 21
    with pytest.raises(impactfe.ResultsError, match=r"VX has no value at t = 1\.25e-05 .*"
                       r"stored in analyses \[1\] but was not written at this point \(OUTRES\)"):
        r.field("VX", time=5 * h)
    with pytest.raises(impactfe.ResultsError, match="SAXL has no value .* not written at this"):
        r.field("SAXL", time=5 * h)
    # Velocities of the TIP component (nodes 15..21) every 10th substep: NaN elsewhere.
    v = r.field("VX", time=10 * h)
    assert list(v.dropna(subset=["VX"]).index) == list(range(15, 22))
    # Reactions: the constrained nodes only.
    fx = r.field("FX", time=20 * h)
    assert list(fx.index) == [1]


def test_argument_errors_name_what_exists(helmet):
    r = impactfe.open(helmet)
    with pytest.raises(impactfe.ResultsError, match=r"'XX' is neither a nodal label nor an "
                       r"element item stored in .*SHELL63: TX TY"):
        r.field("XX", time=0.04)
    with pytest.raises(impactfe.ResultsError, match="nodal labels or element items"):
        r.field(["UZ", "SEQV"], time=0.04)
    with pytest.raises(impactfe.ResultsError, match="give item= as a name"):
        r.field(42)
    with pytest.raises(impactfe.ResultsError, match="give item= as a name"):
        r.field([])
    with pytest.raises(impactfe.ResultsError, match=r"set 191 does not exist .*sets 1\.\.190"):
        r.field("UZ", set=191)
    with pytest.raises(impactfe.ResultsError, match="give set= alone"):
        r.field("UZ", time=0.04, set=10)
    with pytest.raises(impactfe.ResultsError, match=r"analysis 2 does not exist .*analyses 1\.\.1"):
        r.field("UZ", time=0.04, analysis=2)
    with pytest.raises(impactfe.ResultsError, match="time must be a number"):
        r.field("UZ", time="late")
    with pytest.raises(impactfe.ResultsError, match="time must be finite"):
        r.field("UZ", time=float("nan"))
    with pytest.raises(impactfe.ResultsError, match="set must be an integer"):
        r.field("UZ", set=1.5)
    with pytest.raises(impactfe.ResultsError, match="no modal results"):
        r.frequencies()
    with pytest.raises(impactfe.ResultsError, match="gap 1 is not stored .* element item FORC"):
        r.history(gap=1)
    with pytest.raises(impactfe.ResultsError, match="node must be an integer"):
        r.history(node="43", item="UZ")


def test_static_reactions_and_stresses_against_the_closed_form(run_deck):
    """tests/verification/static_indeterminate_bar.inp: a bar fixed at x = 0 and 10, P = 1000 at
    x = 4: R1 = -600, R3 = -400, stresses +600 and -400. A static file has no velocities."""
    r = impactfe.open(run_deck(os.path.join(os.path.dirname(DECKS), "verification",
                                            "static_indeterminate_bar.inp"), "static_bar"))
    fx = r.field("FX")
    assert list(fx.index) == [1, 3] and fx.attrs["set"] == 1
    np.testing.assert_allclose(fx["FX"], [-600.0, -400.0], rtol=1e-9)
    np.testing.assert_allclose(r.field("SAXL", time=1.0)["SAXL"], [600.0, -400.0], rtol=1e-9)
    with pytest.raises(impactfe.ResultsError, match=r"VX has no value at t = 1 .*the file has no "
                       r"VX \(it has nodal: UX .* FX .*; LINK180: FORC SAXL"):
        r.field("VX")


def test_every_request_error_says_what_exists(crash1, plate_modes, run_deck):
    r = impactfe.open(crash1)
    with pytest.raises(impactfe.ResultsError, match="analysis 1 of .* holds no data set"):
        r.field("UX", analysis=1)  # a reduced run whose expansion pass holds the sets
    with pytest.raises(impactfe.ResultsError, match="element 99 is not in results file"):
        r.history(element=99, item="SAXL")
    with pytest.raises(impactfe.ResultsError, match="give exactly one of node=, element=, gap="):
        r.history(node=1, element=1, item="UX")
    with pytest.raises(impactfe.ResultsError, match=r"give item= \(UX\.\.ROTZ"):
        r.history(node=1)
    with pytest.raises(impactfe.ResultsError, match=r"give item= \(SAXL"):
        r.history(element=1)
    with pytest.raises(impactfe.ResultsError, match="no energy balance is stored"):
        impactfe.open(plate_modes).energy()
    small = impactfe.open(run_deck(os.path.join(DECKS, "integrity", "small_results.inp"),
                                   "integrity"))
    # The MASS21 stores its kinetic energy KENE only.
    with pytest.raises(impactfe.ResultsError,
                       match=r"element item 'FORC' is not stored for element 3 \(available: KENE\)"):
        small.history(element=3, item="FORC")
    with pytest.raises(impactfe.ResultsError, match=r"mode 1 of analysis 1 \(.* Hz\) holds mode "
                       r"shapes only \(UX\.\.ROTZ\), no element results"):
        small.field("FORC", set=1)
    with pytest.raises(impactfe.ResultsError, match="is not a file"):
        impactfe.open(os.path.dirname(crash1))


def test_a_file_open_in_h5py_with_locking(crash1, tmp_path):
    """HDF5 opens a file once per process: the error says how to open it both ways."""
    path = tmp_path / "crash1.h5"
    shutil.copy(crash1, path)
    with h5py.File(path, "r"):
        with pytest.raises(impactfe.ResultsError, match="cannot open results file .*locking=False"):
            impactfe.open(path)

"""The thesis helmet dropped on a rigid plane with contact elements instead of its ground gap
(issue 16; docs/elements/conta175.md, "The thesis helmet on a rigid plane").

examples/helmet_full.inp (the thesis deck: helmet-ground COMBIN40 68 -> crown 43, k = 1000 lb/in,
GAP = 1.0) against examples/helmet_contact.inp (the same deck with that gap replaced by a rigid
TARGE170 plane z = -1 on a held pilot and CONTA175 penalty contact, FKN = -1000 lb/in per node, on
all 49 helmet nodes) and examples/helmet_contact_autots.inp (the contact deck in one AUTOTS load
step, DELTIM 1e-3 / min 1e-6 / max 4e-3). All three are run here; nothing is taken from an
earlier run. Run with `pytest -s` to see the step history."""
import os
import re

import numpy as np
import pytest

from conftest import EXAMPLES, post, run

GAP_ELEMENT = 86  # the ground COMBIN40 of helmet_full.inp
# helmet_contact.inp numbers: head-helmet gaps 77-85, pilot 86, facet 87, CONTA175 88.. on the
# helmet nodes 19..67 in order, so node 43 (the crown) carries element 88 + 43 - 19.
FIRST_CONTACT, HELMET_NODES = 88, range(19, 68)
CROWN, CROWN_CONTACT = 43, 88 + 43 - 19
HEAD_GAP = 85  # the head-helmet COMBIN40 at the crown (head node 14 -> crown 43)
LAST_STEP = 0.01 / 150  # the constant step of the thesis' last load step (0.07 -> 0.08)


def _closings(series, closed, after=-1.0):
    """Times at which a status series first is `closed` (bool per value) after `after`."""
    for t, v in series.items():
        if t > after and closed(v):
            return t
    return np.nan


@pytest.fixture(scope="module")
def runs(binary, tmp_path_factory):
    out = {}
    for name in ("helmet_full", "helmet_contact", "helmet_contact_autots"):
        d = tmp_path_factory.mktemp(name)
        p = run([binary, "run", os.path.join(EXAMPLES, name + ".inp"), "-o", str(d)])
        out[name] = (str(d / (name + ".h5")), str(d / (name + ".log")), p.stdout)
    return out


def _crown(binary, h5):
    return post(binary, h5, "--nsol", f"{CROWN},UZ").iloc[:, 0]


def test_contact_closes_and_deflects_as_the_gap(binary, runs):
    gap_h5, contact_h5 = runs["helmet_full"][0], runs["helmet_contact"][0]
    gap_stat = post(binary, gap_h5, "--esol", f"{GAP_ELEMENT},STAT").iloc[:, 0]
    stats = post(binary, contact_h5,
                 *[a for n in HELMET_NODES for a in ("--esol", f"{FIRST_CONTACT + n - 19},STAT")])
    # Only the crown lands: the ring next to it (z = 0.0625) keeps >= 0.04 in of clearance, so
    # the 48 other contact nodes stay open and the plane acts on the crown alone, like the gap.
    ever_closed = [c for c in stats.columns if (stats[c] >= 2).any()]
    assert ever_closed == [f"E{CROWN_CONTACT}_STAT"]
    # COMBIN40 STAT 1 = closed; CONTA175 STAT 2 = sliding (frictionless closed contact).
    t_gap = _closings(gap_stat, lambda v: v >= 0.5)
    t_contact = _closings(stats[f"E{CROWN_CONTACT}_STAT"], lambda v: v >= 2)
    # First closure within one step of the gap model (measured: the same substep, 0.072000; the
    # exact free-fall time is 0.071944).
    assert abs(t_contact - t_gap) <= LAST_STEP + 1e-12, (t_contact, t_gap)
    assert 0.071944 - 1e-12 <= t_contact <= 0.071944 + LAST_STEP
    # Peak crown displacement of the first impact and the whole crown history: within 0.1 % of
    # the 1.0 in travel (measured: equal to round-off, both -1.0093874 at 0.072533, because
    # penalty contact with the gap's stiffness on the one node that lands is the gap's law).
    uz_gap, uz_contact = _crown(binary, gap_h5), _crown(binary, contact_h5)
    first = (uz_gap.index > 0.0719) & (uz_gap.index < 0.0731)
    assert abs(uz_contact[first].min() - uz_gap[first].min()) <= 1e-3
    assert np.allclose(uz_gap.index.values, uz_contact.index.values)
    assert np.max(np.abs(uz_contact.values - uz_gap.values)) <= 1e-3
    # The force on the crown is the gap's (FN > 0 compression vs COMBIN40 FORC < 0).
    fn = post(binary, contact_h5, "--esol", f"{CROWN_CONTACT},FN").iloc[:, 0]
    forc = post(binary, gap_h5, "--esol", f"{GAP_ELEMENT},FORC").iloc[:, 0]
    assert np.max(np.abs(fn.values + forc.values)) <= 1e-3 * np.max(np.abs(forc.values))


def test_autots_small_steps_only_around_impacts(binary, runs):
    auto_h5, auto_log, stdout = runs["helmet_contact_autots"]
    series = post(binary, auto_h5, "--nsol", f"{CROWN},UZ", "--esol", f"{CROWN_CONTACT},STAT",
                  "--esol", f"{HEAD_GAP},STAT")
    t = series.index.values
    assert t[0] == 0.0 and abs(t[-1] - 0.08) < 1e-12
    dt = np.diff(t)
    ground = series.iloc[1:, 1].values >= 2  # status at the end of each step
    head = series.iloc[1:, 2].values >= 0.5
    in_contact = ground | head
    print("\nAUTOTS step history (helmet_contact_autots): t_end, dt, crown UZ, ground, head")
    for k in range(len(dt)):
        print(f"  {t[k + 1]:.6f} {dt[k]:.3e} {series.iloc[k + 1, 0]:+.5f} "
              f"{'closed' if ground[k] else 'open  '} {'closed' if head[k] else 'open'}")
    log = open(auto_log).read()
    summary = re.search(r"automatic time stepping, load step 1: (\d+) substeps, (\d+) cuts", log)
    assert summary and int(summary.group(1)) == len(dt)
    cuts = re.findall(r"dt = \S+ cut to \S+: (.*)", log)
    assert len(cuts) == int(summary.group(2)) and cuts
    print(f"  {len(dt)} substeps, {len(cuts)} cuts; first cut: {cuts[0]}")

    free_fall = dt[t[1:] < 0.070]  # before the first impact (0.071944)
    contact_steps = dt[in_contact]
    assert contact_steps.size > 10
    # Large steps in the free fall (the largest allowed, 4e-3, reached), small in contact: the
    # median free-fall step is >= 20x the largest step ending with a contact closed (measured
    # 3.99e-3 vs 7.3e-5, 55x: the ceiling T/30 of the crown's ground-contact frequency).
    assert np.max(free_fall) > 3.9e-3
    assert np.median(free_fall) >= 20 * np.max(contact_steps)
    # Between the first rebound (ground opens ~0.0731) and the head closing (~0.0743) the step
    # grows again: at least 2x the contact ceiling (measured 1.8e-4, 2.5x; 2.7e-4 in the step
    # the head closes in).
    between = dt[(t[1:] > 0.07315) & (t[1:] < 0.07430)]
    assert between.size and np.max(between) >= 2 * np.max(contact_steps)
    # The first impact is resolved: closure within one contact step of the free-fall time and
    # the crown minimum within 0.1 % of the 1.0 in travel of the constant-step contact run
    # (measured -1.00919 vs -1.00939).
    t_close = _closings(series.iloc[:, 1], lambda v: v >= 2)
    assert 0.071944 - 1e-12 <= t_close <= 0.071944 + np.max(contact_steps)
    uz_auto = series.iloc[:, 0]
    uz_const = _crown(binary, runs["helmet_contact"][0])
    first = lambda s: s[(s.index > 0.0719) & (s.index < 0.0731)].min()  # noqa: E731
    assert abs(first(uz_auto) - first(uz_const)) <= 1e-3

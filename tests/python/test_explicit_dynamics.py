"""Explicit dynamics (docs/explicit_dynamics.md) against independent references: the first
period of a SOLID164 cantilever against impactfe's own modal analysis of the same mesh
(SOLID185, incompatible modes), and the energy balance of the explicit runs (total energy
within 1 % of what was put in, hourglass energy under 10 % of the internal energy)."""
import os

import numpy as np
import pytest

import impactfe
from conftest import DECKS, ROOT

CANTILEVER = os.path.join(DECKS, "explicit", "cantilever_modal_and_explicit.inp")
BAR = os.path.join(ROOT, "tests", "verification", "explicit_bar_wave_solid164.inp")
SHELL_CANTILEVER = os.path.join(DECKS, "explicit", "shell163_cantilever_modal_and_explicit.inp")


def crossings(t, u):
    """Times where u changes sign (linear interpolation)."""
    out = []
    for k in range(1, len(u)):
        if u[k - 1] > 0 >= u[k] or u[k - 1] < 0 <= u[k]:
            out.append(t[k - 1] + (t[k] - t[k - 1]) * u[k - 1] / (u[k - 1] - u[k]))
    return out


def test_cantilever_period_matches_the_modal_analysis(run_deck):
    """The one-point brick has a constant strain per element: across n = 4 layers of the
    thickness the bending strain is a staircase, so the section's second moment is that of the
    layers' centres, sum (h/n) y_i^2 = (1 - 1/n^2) h^3/12, and the one-point mesh's bending
    frequency is sqrt(1 - 1/n^2) = 0.9682 times that of a mesh with a linear strain across
    each element (SOLID185 with incompatible modes). Measured: 78.91 Hz against
    81.64 x 0.9682 = 79.04 Hz (modal, lumped mass): -0.2 %."""
    r = impactfe.open(run_deck(CANTILEVER, "cantilever"))
    f1 = float(r.frequencies()["frequency_hz"].iloc[0])
    # The tip node on the beam's axis line at x = L: the node of largest x (any of them).
    nodes = r.nodes()
    tip = int(nodes["X"].idxmax())
    h = r.history(node=tip, item="UY")
    t, u = h.index.to_numpy(), h.iloc[:, 0].to_numpy()
    z = crossings(t[1:], u[1:])  # u starts at 0: the first crossing is at T/2
    assert len(z) >= 2, z
    period = z[1] - z[0]  # T/2 apart
    period = 2 * period
    print(f"f1 modal {f1:.2f} Hz, explicit {1 / period:.2f} Hz")
    assert 1 / period == pytest.approx(f1 * (1 - 1 / 4**2) ** 0.5, rel=0.01)


def test_shell163_cantilever_period_matches_the_modal_analysis(run_deck):
    """SHELL163 (one in-plane point, 3 Gauss points through the thickness) against the SHELL181
    modal analysis of the same 20 x 2 mesh (lumped mass): 8.222 Hz; beam theory for the strip,
    3.516/(2 pi) sqrt(E t^2/(12 rho))/L^2 = 8.18 Hz. Measured: 8.16-8.18 Hz (-0.6 %) over the
    first three half periods. The scaled rotary inertia (A + t^2)/6 per unit mass lowers it by
    about (L_e k)^2/12 = 0.1 %."""
    r = impactfe.open(run_deck(SHELL_CANTILEVER, "shell163_cantilever"))
    f1 = float(r.frequencies()["frequency_hz"].iloc[0])
    nodes = r.nodes()
    tip = int(nodes["X"].idxmax())
    h = r.history(node=tip, item="UZ")
    t, u = h.index.to_numpy(), h.iloc[:, 0].to_numpy()
    z = crossings(t[1:], u[1:])
    assert len(z) >= 3, z
    period = (z[2] - z[0])  # two half periods
    print(f"f1 modal {f1:.3f} Hz, explicit {1 / period:.3f} Hz")
    assert 1 / period == pytest.approx(f1, rel=0.015)
    # The clamped edge: rotations stay 0 and carry the bending moment as a reaction.
    root = int(nodes["X"].idxmin())
    assert abs(r.history(node=root, item="ROTY").iloc[:, 0]).max() == 0.0
    tip_rotation = r.history(node=tip, item="ROTY").iloc[:, 0]
    assert abs(tip_rotation).max() > 0.0


@pytest.mark.parametrize("deck", [BAR, CANTILEVER, SHELL_CANTILEVER])
def test_energy_balance_and_hourglass(run_deck, deck):
    e = impactfe.open(run_deck(deck, os.path.basename(deck)[:-4])).energy()
    e = e[e["analysis"] == e["analysis"].max()]
    put_in = (e["initial_kinetic"] + e["external_work"]).max()
    assert put_in > 0
    worst = (e["numerical"].abs() / put_in).max()
    internal = e["strain"] + e["plastic_work"].fillna(0.0)
    last = e.iloc[-1]
    print(f"{os.path.basename(deck)}: balance off by at most {100 * worst:.3f} %, hourglass "
          f"{last['dissipation']:.4g}, largest internal {internal.max():.4g}")
    assert worst < 0.01
    # Against the largest internal energy of the run (the cantilever's internal energy passes
    # through ~0 every half period, when the hourglass work it has dissipated stays).
    assert last["dissipation"] < 0.10 * internal.max()


def test_contact_forces_are_stored_per_contact(run_deck, binary):
    """The block drop (EDCGEN,ASTS,1,2): the force on the contact surface (the impactor, part 1)
    pushes it up, by symmetry straight up (the sideways components 2.6e-4 of the peak: the
    quadrilateral segments' projections are not symmetric); `impactfe post --rcforc` prints the
    same series as the reader's history(contact=)."""
    from conftest import run

    h5 = run_deck(os.path.join(ROOT, "tests", "verification",
                               "explicit_contact_blocks_solid164.inp"), "blocks")
    df = impactfe.open(h5).history(contact=1, item=["FX", "FY", "FZ"])
    assert list(df.columns) == ["CONTACT1_FX", "CONTACT1_FY", "CONTACT1_FZ"]
    peak = df["CONTACT1_FZ"].max()
    assert peak > 1e4 and df["CONTACT1_FZ"].min() >= 0.0
    assert df[["CONTACT1_FX", "CONTACT1_FY"]].abs().max().max() < 1e-3 * peak
    csv = run([binary, "post", h5, "--rcforc", "1,FZ"]).stdout.splitlines()
    assert csv[0] == "time,CONTACT1_FZ"
    values = [float(line.split(",")[1]) for line in csv[1:]]
    assert np.allclose(values, df["CONTACT1_FZ"].to_numpy(), rtol=1e-9, atol=0.0)
    run([binary, "post", h5, "--rcforc", "2,FZ"], expect=1)


def test_part_energies_add_up_to_the_balance(run_deck, binary):
    """The block drop's two parts (EDPART: the impactor 1, the target 2): their kinetic,
    internal and hourglass energies add up, at every stored point, to the run's kinetic, strain
    plus plastic and hourglass energies; at the start the impactor has all of it, ½ m1 v0² =
    0.78."""
    from conftest import run

    h5 = run_deck(os.path.join(ROOT, "tests", "verification",
                               "explicit_contact_blocks_solid164.inp"), "blocks")
    r = impactfe.open(h5)
    parts = {p: r.history(part=p, item=["KE", "IE", "HE"]) for p in (1, 2)}
    e = r.energy()
    e = e[e["analysis"] == e["analysis"].max()]
    total = parts[1].to_numpy() + parts[2].to_numpy()
    assert np.allclose(total[:, 0], e["kinetic"].to_numpy(), rtol=0, atol=1e-12)
    internal = e["strain"] + e["plastic_work"].fillna(0.0)
    assert np.allclose(total[:, 1], internal.to_numpy(), rtol=0, atol=1e-12)
    assert np.allclose(total[:, 2], e["dissipation"].to_numpy(), rtol=0, atol=1e-12)
    assert parts[1]["PART1_KE"].iloc[0] == pytest.approx(0.78, rel=1e-12)
    assert parts[2]["PART2_KE"].iloc[0] == 0.0
    csv = run([binary, "post", h5, "--part", "2,HE"]).stdout.splitlines()
    assert csv[0] == "time,PART2_HE" and len(csv) == len(parts[2]) + 1
    run([binary, "post", h5, "--part", "3,KE"], expect=1)


def test_results_are_bitwise_equal_for_any_thread_count(binary, tmp_path):
    """The element loop runs in chunks of 256 elements on the thread pool; each element writes
    its own force slots and each chunk its own energy sums, taken in chunk order
    (docs/explicit_dynamics.md, "Determinism"): the Taylor bar's 1440 bricks (6 chunks) give the
    same file, bit for bit, on one thread and on two."""
    import subprocess

    import h5py

    deck = os.path.join(ROOT, "tests", "verification", "explicit_taylor_bar_solid164.inp")
    files = []
    for threads in (1, 2):
        out = tmp_path / ("threads%d" % threads)
        subprocess.run([binary, "run", deck, "-o", str(out), "--threads", str(threads)],
                       check=True, capture_output=True)
        files.append(h5py.File(out / "explicit_taylor_bar_solid164.h5", "r"))
    compared = []

    def check(name, obj):
        if isinstance(obj, h5py.Dataset) and obj.dtype.kind in "fiu":
            a, b = obj[()], files[1][name][()]
            assert np.array_equal(a, b, equal_nan=True), name
            compared.append(name)

    files[0].visititems(check)
    assert any("displacement" in n for n in compared) or len(compared) > 10, compared

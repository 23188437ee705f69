"""MAPDL session commands that are carried out, ignored with a reason, or refused: /UNITS is kept
in the results file (info, Python); /CONFIG and /NERR are logged with why they do nothing here."""
import os
import sys

from conftest import ROOT, run

sys.path.insert(0, os.path.join(ROOT, "python"))
import impactfe  # noqa: E402

DECK = """/UNITS,{units}
/CONFIG,NRES,5000
/NERR,5,1000
/PREP7
ET,1,LINK180
R,1,1.0
MP,EX,1,200E9
N,1
N,2,1
E,1,2
D,1,ALL
D,2,UY,,,,,UZ
F,2,FX,1000
FINISH
/SOLU
SOLVE
FINISH
"""


def _run(binary, tmp_path, units):
    deck = tmp_path / "bar.inp"
    deck.write_text(DECK.format(units=units))
    p = run([binary, "run", str(deck), "-o", str(tmp_path)])
    return p, str(tmp_path / "bar.h5"), (tmp_path / "bar.log").read_text()


def test_units_label_is_kept(binary, tmp_path):
    _, h5, log = _run(binary, tmp_path, "SI")
    assert "unit system SI recorded" in log
    assert "/CONFIG: accepted and ignored: MAPDL's memory and file sizing" in log
    assert "/NERR: accepted and ignored: error limits" in log
    assert impactfe.open(h5).units == "SI"
    info = run([binary, "info", h5]).stdout
    assert "Units: SI (/UNITS)" in info
    # The answer does not depend on the label: nothing is converted (u = F L / (E A)).
    ux = impactfe.open(h5).history(node=2, item="UX")["N2_UX"].iloc[-1]
    assert abs(ux - 1000 / 200e9) < 1e-12 * 1000 / 200e9 + 1e-20


def test_micro_mks_label_and_no_label(binary, tmp_path):
    _, h5, _ = _run(binary, tmp_path, "umks")
    assert impactfe.open(h5).units == "uMKS"
    deck = tmp_path / "plain.inp"
    deck.write_text(DECK.replace("/UNITS,{units}\n", ""))
    run([binary, "run", str(deck), "-o", str(tmp_path)])
    plain = str(tmp_path / "plain.h5")
    assert impactfe.open(plain).units == ""
    assert "Units:" not in run([binary, "info", plain]).stdout

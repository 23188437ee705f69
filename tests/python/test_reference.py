"""The command and element reference is generated from the registries: docs/reference.md is the
output of `impactfe help --markdown` (regenerate it with
`./build/impactfe help --markdown > docs/reference.md`), and `impactfe help NAME` answers for a
command, an abbreviation, an element type, a skippable unknown command and a name it does not
know."""
import os

from conftest import ROOT, run


def test_reference_page_is_generated(binary):
    generated = run([binary, "help", "--markdown"]).stdout
    with open(os.path.join(ROOT, "docs", "reference.md")) as f:
        assert f.read() == generated, (
            "docs/reference.md is out of date: ./build/impactfe help --markdown > docs/reference.md")
    assert "| `NSUBST` |" in generated and "### SOLID185" in generated


def test_help_on_a_command(binary):
    out = run([binary, "help", "nsubst"]).stdout
    assert out.startswith("NSUBST\n") and "carried out" in out and "/SOLU" in out
    assert "refused: not carried out" in run([binary, "help", "/CWD"]).stdout
    assert "accepted and ignored: MAPDL's memory and file sizing" in run(
        [binary, "help", "/CONFIG"]).stdout
    assert "--skip-unknown skips it" in run([binary, "help", "JPGPRF"]).stdout


def test_help_on_an_element(binary):
    out = run([binary, "help", "solid185"]).stdout
    assert out.startswith("### SOLID185") and "KEYOPT(2)" in out
    link = run([binary, "help", "LINK180"]).stdout
    assert "1 AREA 2 ADDMAS 3 TENSKEY" in link


def test_help_on_an_unknown_name(binary):
    p = run([binary, "help", "NOSUCH"], expect=1)
    assert "neither a command nor an element type" in p.stderr

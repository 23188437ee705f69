"""Fixtures of the Python tests (run by ctest with /usr/bin/python3 -m pytest, see
tests/CMakeLists.txt): the impactfe binary, decks run once per session, `impactfe post` as
numbers."""
import io
import os
import subprocess

import pandas as pd
import pytest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXAMPLES = os.path.join(ROOT, "examples")
DECKS = os.path.join(ROOT, "tests", "decks")


@pytest.fixture(scope="session")
def binary():
    path = os.environ.get("IMPACTFE_BINARY", os.path.join(ROOT, "build", "impactfe"))
    assert os.path.exists(path), f"impactfe binary not found: {path} (set IMPACTFE_BINARY)"
    return path


def run(args, expect=0):
    p = subprocess.run(args, capture_output=True, text=True)
    assert p.returncode == expect, f"{' '.join(args)} exited {p.returncode}:\n{p.stdout}{p.stderr}"
    return p


@pytest.fixture(scope="session")
def run_deck(binary, tmp_path_factory):
    """run_deck(path, name) -> results file of the deck, run once per session in its own dir."""
    done = {}

    def go(deck, name=None, directory=None):
        key = (deck, directory)
        if key not in done:
            out = directory or str(tmp_path_factory.mktemp(name or "run"))
            run([binary, "run", deck, "-o", out])
            stem = os.path.splitext(os.path.basename(deck))[0]
            done[key] = os.path.join(out, stem + ".h5")
        return done[key]

    return go


@pytest.fixture(scope="session")
def helmet(run_deck):
    """The helmet example's results: the report test's run when ctest gives it, else a run."""
    given = os.environ.get("IMPACTFE_HELMET_RESULTS")
    if given and os.path.exists(given):
        return given
    return run_deck(os.path.join(EXAMPLES, "helmet_full.inp"), "helmet")


@pytest.fixture(scope="session")
def crash1(run_deck):
    return run_deck(os.path.join(EXAMPLES, "crash1.inp"), "crash1")


def post(binary, results, *requests):
    """`impactfe post` CSV as a DataFrame indexed by time."""
    p = run([binary, "post", results, *requests])
    return pd.read_csv(io.StringIO(p.stdout), index_col=0)


@pytest.fixture(scope="session")
def plate_drop(run_deck):
    """A SHELL181 plate dropped at 5 m/s (IC) on a sloped rigid CONTA174/TARGE170 floor: the
    report test's run when ctest gives it, else a run."""
    given = os.environ.get("IMPACTFE_PLATE_DROP_RESULTS")
    if given and os.path.exists(given):
        return given
    return run_deck(os.path.join(EXAMPLES, "plate_drop.inp"), "plate_drop")


@pytest.fixture(scope="session")
def plate_modes(run_deck):
    """Modal analysis of the same plate, simply supported."""
    return run_deck(os.path.join(EXAMPLES, "plate_modes.inp"), "plate_modes")

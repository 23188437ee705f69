"""The Python package on damaged results files (docs/python.md, "Errors"): every failure of the
file is an impactfe.ResultsError naming the file, never a raw h5py OSError or KeyError, and never
other numbers without an error. Each way a file can be damaged is made on purpose; then random
8-byte corruptions of a small file with every kind of dataset (tests/decks/integrity, the file
of tests/unit/test_results_integrity.cpp) are either harmless or reported."""
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np
import pytest

import impactfe
from conftest import DECKS, ROOT

HERE = os.path.dirname(os.path.abspath(__file__))


@pytest.fixture(scope="module")
def small(run_deck):
    return run_deck(os.path.join(DECKS, "integrity", "small_results.inp"), "integrity")


@pytest.fixture
def copy(small, tmp_path):
    path = tmp_path / "copy.h5"
    shutil.copy(small, path)
    return str(path)


def test_missing_and_foreign_files(tmp_path):
    with pytest.raises(impactfe.ResultsError, match="results file '.*nothing.h5' does not exist"):
        impactfe.open(tmp_path / "nothing.h5")
    text = tmp_path / "text.h5"
    text.write_text("not HDF5\n")
    with pytest.raises(impactfe.ResultsError, match=r"is not an impactfe results file \(not HDF5"):
        impactfe.open(text)
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["x"] = np.zeros(3)
    with pytest.raises(impactfe.ResultsError, match="other.h5' is not an impactfe results file$"):
        impactfe.open(other)


def test_newer_format_version(copy):
    with h5py.File(copy, "r+") as f:
        f.attrs["format_version"] = 3
    with pytest.raises(impactfe.ResultsError, match=r"has format version 3; this package reads "
                       r"versions \(1, 2\)"):
        impactfe.open(copy)


@pytest.mark.parametrize("fraction", [0.999, 0.5, 0.05, 0.0])
def test_truncated_file(small, copy, fraction):
    os.truncate(copy, int(os.path.getsize(small) * fraction))
    with pytest.raises(impactfe.ResultsError) as e:
        r = impactfe.open(copy)
        r.energy()
        r.field("UX")
    assert "truncated" in str(e.value) or "damaged" in str(e.value) or \
        "not HDF5" in str(e.value), e.value


def test_a_missing_model_table(copy):
    with h5py.File(copy, "r+") as f:
        del f["model/node_coordinates"]
    with pytest.raises(impactfe.ResultsError, match=r"copy.h5' is damaged or incomplete: "
                       r"KeyError: .*node_coordinates"):
        impactfe.open(copy)


def test_model_tables_that_disagree(copy):
    with h5py.File(copy, "r+") as f:
        ids = f["model/element_ids"][:]
        del f["model/element_ids"]
        f["model/element_ids"] = ids[:-1]
    with pytest.raises(impactfe.ResultsError, match=r"damaged or incomplete: ValueError: "
                       r"/model/element_type_names has 3 rows for 2 elements"):
        impactfe.open(copy)


def _chunk(path, name, coord):
    with h5py.File(path, "r") as f:
        ds = f[name]
        return ds.id.get_chunk_info_by_coord(coord), ds.chunks


def test_a_block_that_fails_its_checksum(copy):
    info, _ = _chunk(copy, "analysis_2/U", (0, 0, 0))
    with open(copy, "r+b") as f:
        f.seek(info.byte_offset + 5)
        byte = f.read(1)
        f.seek(info.byte_offset + 5)
        f.write(bytes([byte[0] ^ 0xFF]))
    r = impactfe.open(copy)  # the model and time axes are intact
    with pytest.raises(impactfe.ResultsError, match=r"damaged or incomplete: OSError: .*Fletcher32"):
        r.history(node=3, item="UX")
    with pytest.raises(impactfe.ResultsError, match="damaged or incomplete"):
        r.field("UX", time=0.0)


def _rewrite(path, name, keep):
    """Replaces dataset `name` by a copy with the same layout where only the chunks `keep`
    selects are written: the others are missing from the chunk index (a corrupted index entry
    reads so), and read as the fill value NaN without the check."""
    with h5py.File(path, "r+") as f:
        ds = f[name]
        data, chunks, fill = ds[()], ds.chunks, ds.fillvalue
        del f[name]
        new = f.create_dataset(name, shape=data.shape, maxshape=(None,) + data.shape[1:],
                               chunks=chunks, fletcher32=True, fillvalue=fill, dtype=data.dtype)
        for start in range(0, data.shape[0], chunks[0]):
            if keep(start):
                new[start:start + chunks[0]] = data[start:start + chunks[0]]


def test_a_chunk_missing_from_the_index(copy):
    _rewrite(copy, "analysis_2/U", keep=lambda start: start > 0)
    r = impactfe.open(copy)
    with pytest.raises(impactfe.ResultsError, match=r"chunk index entry of /analysis_2/U is "
                       r"corrupted \(a chunk is missing\)"):
        r.history(node=3, item="UX")
    with pytest.raises(impactfe.ResultsError, match="a chunk is missing"):
        r.field("UX", time=0.0)


def test_a_chunk_whose_filters_are_skipped(copy):
    """A chunk index entry whose filter mask is not 0 makes HDF5 skip the checksum."""
    name = "analysis_2/energy"
    info, chunks = _chunk(copy, name, (0, 0))
    with h5py.File(copy, "r+") as f:
        ds = f[name]
        raw = np.ascontiguousarray(np.zeros(chunks)).tobytes()
        ds.id.write_direct_chunk(info.chunk_offset, raw, filter_mask=0xFFFF)
    with pytest.raises(impactfe.ResultsError, match=r"chunk index entry of /analysis_2/energy is "
                       r"corrupted \(its filter mask is not 0\)"):
        impactfe.open(copy).energy()


def test_a_missing_analysis_attribute_or_family(copy):
    with h5py.File(copy, "r+") as f:
        del f["analysis_2/elements"][list(f["analysis_2/elements"])[0]]["element_ids"]
    with pytest.raises(impactfe.ResultsError, match=r"damaged or incomplete: KeyError"):
        impactfe.open(copy)


def test_random_corruption_is_harmless_or_reported(small, tmp_path):
    """60 copies of the file with 8 random bytes overwritten each: every public call of the
    package (model tables, sets, energy, modes, the history of every node and element, the
    fields of every label and item at five sets) gives what it gives for the intact file, or
    a ResultsError; never another exception, other numbers, or a crash (the copies are read in
    a child process)."""
    p = subprocess.run([sys.executable, os.path.join(HERE, "results_probe.py"), small,
                        str(tmp_path), "20261202", "60"],
                       capture_output=True, text=True, timeout=400,
                       env=dict(os.environ, PYTHONPATH=os.path.join(ROOT, "python")))
    lines = [line.split(" ", 2) for line in p.stdout.splitlines()[1:]]
    outcomes = [line for line in lines if line[1] != "start"]
    assert p.returncode == 0, f"the probe crashed at the copy of offset {lines[-1][0]}:\n" \
        f"{p.stderr}"
    assert len(outcomes) == 60
    bad = [" ".join(line) for line in outcomes if line[1] not in ("same", "reported")]
    assert not bad, "\n".join(bad)
    reported = [line for line in outcomes if line[1] == "reported"]
    assert len(reported) >= 10  # most of the file is checksummed data and metadata
    assert all("results file" in line[2] for line in reported)

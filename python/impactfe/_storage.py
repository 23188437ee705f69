"""The results file as stored: opening it, reading its datasets with the integrity checks of the
C++ reader (src/results/results_reader.cpp, src/io/h5_util.cpp: verify_chunk_index), the model
tables and one object per /analysis_<k> group. Schema: docs/results_file.md."""
import functools
import itertools
import os

import h5py
import numpy as np

FORMAT_VERSIONS = (1, 2)

#: What h5py (and numpy on the arrays it returns) raise on a damaged or truncated file: a chunk
#: that fails its Fletcher32 checksum (OSError), an object whose header is gone (KeyError), a
#: dataset or attribute of the wrong shape or type (ValueError, TypeError, IndexError), an HDF5
#: failure without a Python class of its own (RuntimeError).
FILE_ERRORS = (OSError, KeyError, ValueError, TypeError, IndexError, RuntimeError)


class ResultsError(Exception):
    """A request the file cannot answer (unknown node, item, time, ...) or a damaged file; the
    message says what the file has."""


ResultsError.__module__ = "impactfe"


def damaged(path, error):
    """The error for an HDF5 failure while reading: the words of the C++ reader."""
    return ResultsError(f"results file '{path}' is damaged or incomplete: "
                        f"{type(error).__name__}: {error} (a corrupted block fails its checksum; "
                        "re-run the job to rewrite it)")


def guarded(method):
    """Runs a public method; a failure of the file becomes a ResultsError naming the file. The
    method validates its own arguments first (a ResultsError passes through unchanged)."""
    @functools.wraps(method)
    def wrapper(self, *args, **kwargs):
        try:
            return method(self, *args, **kwargs)
        except ResultsError:
            raise
        except FILE_ERRORS as e:
            raise damaged(self.path, e) from e
    return wrapper


def integer(value, what):
    """`value` as an int (Python or numpy integers only), or a ResultsError naming `what`."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise ResultsError(f"{what} must be an integer, not {value!r}")
    return int(value)


def text(value):
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8", "replace").rstrip("\0")
    return str(value)


def _slab(shape, index):
    """(start, count) per dimension of `index` (ints and slices with step 1) into `shape`."""
    index = tuple(index) + (slice(None),) * (len(shape) - len(index))
    start, count = [], []
    for i, n in zip(index, shape):
        if isinstance(i, slice):
            first, stop, _ = i.indices(n)
            start.append(first)
            count.append(max(0, stop - first))
        else:
            start.append(int(i))
            count.append(1)
    return start, count


def verify_chunks(ds, index, require_all):
    """Checks the chunk index entries of the chunks that `ds[index]` reads, as the C++ reader
    does: the chunk index (a v1 B-tree) is the one structure of the file without a checksum. An
    entry whose filter mask is not 0 would skip the checksum; a chunk missing from a dataset
    written whole (`require_all`) would read as the fill value (NaN: "absent") instead of an
    error."""
    if ds.chunks is None or not hasattr(ds.id, "get_chunk_info_by_coord"):
        return  # (h5py before 3.0 or HDF5 before 1.10.5 cannot look chunks up)
    start, count = _slab(ds.shape, index)
    if any(c == 0 for c in count):
        return
    ranges = [range(s // c, (s + n - 1) // c + 1) for s, n, c in zip(start, count, ds.chunks)]
    for at in itertools.product(*ranges):
        info = ds.id.get_chunk_info_by_coord(tuple(a * c for a, c in zip(at, ds.chunks)))
        if info.byte_offset is not None and info.filter_mask != 0:
            raise OSError(f"a chunk index entry of {ds.name} is corrupted (its filter mask is not 0)")
        if require_all and info.byte_offset is None:
            raise OSError(f"a chunk index entry of {ds.name} is corrupted (a chunk is missing)")


def read(ds, index=(), require_all=True):
    """ds[index] after verify_chunks; `require_all`: every chunk of the slab was written."""
    verify_chunks(ds, index, require_all)
    return ds[tuple(index)] if index else ds[()]


def read_strings(ds):
    return [text(x) for x in read(ds)]


def open_file(path):
    """The h5py file, opened without the HDF5 file lock (a running job holds it while it writes
    the file), or a ResultsError that says why it cannot be read."""
    if not os.path.exists(path):
        raise ResultsError(f"results file '{path}' does not exist")
    if not os.path.isfile(path):
        raise ResultsError(f"results file '{path}' is not a file")
    try:
        is_hdf5 = h5py.is_hdf5(path)
    except OSError as e:
        raise ResultsError(f"cannot read results file '{path}': {e}") from e
    if not is_hdf5:
        raise ResultsError(f"'{path}' is not an impactfe results file (not HDF5)")
    try:
        return h5py.File(path, "r", locking=False)
    except OSError as e:
        if "truncated" in str(e):
            raise ResultsError(
                f"results file '{path}' is truncated ({os.path.getsize(path)} bytes; HDF5 says: "
                f"{e}): the run that wrote it stopped while the file grew, or the file was cut "
                "short when copied") from e
        hint = ""
        if "locking" in str(e):  # HDF5 opens a file once per process, with one locking mode
            hint = (" (the file is open in this process through h5py with file locking: close "
                    "it, or open it with h5py.File(path, 'r', locking=False))")
        raise ResultsError(f"cannot open results file '{path}': {e}{hint}") from e


class Model:
    """The /model tables, read whole and checked against each other."""

    def __init__(self, f):
        g = f["model"]
        self.node_ids = read(g["node_ids"]).astype(np.int64)
        self.node_coordinates = read(g["node_coordinates"])
        self.element_ids = read(g["element_ids"]).astype(np.int64)
        self.element_type_names = read_strings(g["element_type_names"])
        self.element_types = read(g["element_types"])
        self.element_materials = read(g["element_materials"])
        self.element_reals = read(g["element_reals"])
        self.element_nodes = read(g["element_nodes"])
        n, e = len(self.node_ids), len(self.element_ids)
        if self.node_coordinates.shape != (n, 3):
            raise ValueError(f"/model/node_coordinates has shape {self.node_coordinates.shape} "
                             f"for {n} nodes")
        for name in ("element_type_names", "element_types", "element_materials",
                     "element_reals", "element_nodes"):
            if len(getattr(self, name)) != e:
                raise ValueError(f"/model/{name} has {len(getattr(self, name))} rows for {e} "
                                 "elements")
        for name, ids in (("node_ids", self.node_ids), ("element_ids", self.element_ids)):
            if len(ids) > 1 and not np.all(np.diff(ids) > 0):
                raise ValueError(f"/model/{name} is not ascending")

    def node_rows(self, nodes):
        """Rows of user node numbers; ValueError when one is not a node of the model."""
        return _rows(self.node_ids, nodes, "node")

    def element_rows(self, elements):
        """Rows of user element numbers; ValueError when one is not an element of the model."""
        return _rows(self.element_ids, elements, "element")


def _rows(ids, wanted, what):
    wanted = np.asarray(wanted, dtype=np.int64)
    rows = np.searchsorted(ids, wanted)
    ok = rows < len(ids)
    ok[ok] = ids[rows[ok]] == wanted[ok]
    if not np.all(ok):
        raise ValueError(f"the model has no {what} {wanted[~ok][0]}")
    return rows


class Family:
    """/analysis_<k>/elements/<family>: its element ids and item names."""

    def __init__(self, name, group):
        self.name = name
        self.element_ids = read(group["element_ids"]).astype(np.int64)
        self.items = read_attribute_strings(group, "items")
        self.upper = [x.upper() for x in self.items]
        self.row = {int(e): i for i, e in enumerate(self.element_ids)}


def read_attribute_strings(obj, name):
    return [text(x) for x in np.atleast_1d(obj.attrs[name])]


class Analysis:
    """One /analysis_<k> group: its times, load steps and substeps, and where its rows live."""

    def __init__(self, group, index, n_nodes):
        self.group = group
        self.index = index
        self.kind = text(group.attrs.get("kind", ""))
        self.status = text(group.attrs.get("status", ""))
        self.description = text(group.attrs.get("description", ""))
        self.n_nodes = n_nodes
        # Every chunk of a main dataset is written (NaN blocks included) by writers that mark
        # the group so; older files may leave never-written chunks out.
        self.all_chunks_written = "all_chunks_written" in group.attrs
        n_t = 0
        self.times = np.zeros(0)
        self.load_steps = np.zeros(0, dtype=np.int64)
        self.substeps = np.zeros(0, dtype=np.int64)
        if "time" in group:
            self.times = read(group["time"])
            n_t = len(self.times)
            # Crash consistency: `time` is written last, so its length is the number of
            # complete points; the other per-point datasets may be longer after a kill.
            for name in ("load_step", "substep"):
                if name in group:
                    values = read(group[name], (slice(0, n_t),)).astype(np.int64)
                    if len(values) != n_t:
                        raise ValueError(f"{group.name}/{name} has {len(values)} of {n_t} points")
                    setattr(self, name + "s", values)
                else:
                    setattr(self, name + "s", np.ones(n_t, dtype=np.int64))
        # Format 2: points from first_row on are still in the staging datasets under recent/
        # (a job that is running or was killed); all points are in the main datasets otherwise.
        self.first_recent = n_t
        if "recent" in group and "first_row" in group["recent"].attrs:
            self.first_recent = int(group["recent"].attrs["first_row"])
        self.reaction_columns = None
        if "reaction_dofs" in group:
            rd = read(group["reaction_dofs"])
            self.reaction_columns = {(int(n), int(d)): c for c, (n, d) in enumerate(rd)}
        self.families = []
        if "elements" in group:
            for name, fam in group["elements"].items():
                self.families.append(Family(name, fam))
        self.n_modes = group["frequencies"].shape[0] if "frequencies" in group else 0

    def initial_row(self):
        """Row of the initial state (t = 0, load step 0) a transient stores first, or None."""
        rows = np.flatnonzero(self.load_steps == 0)
        return int(rows[0]) if len(rows) else None

    def rows(self, name, index=(), points=None):
        """Values of dataset `name` at the time points `points` (a slice of rows; all by
        default), sliced by `index` along the other dimensions; NaN where absent, None when the
        analysis has no such dataset."""
        n_t = len(self.times)
        first, stop, _ = (points or slice(None)).indices(n_t)
        stop = max(first, stop)
        out = None
        split = min(max(self.first_recent, first), stop)
        parts = [(name, first, first, split - first, self.all_chunks_written),
                 ("recent/" + name, split, split - self.first_recent, stop - split, False)]
        for path, at, file_first, count, whole in parts:
            if count <= 0 or path not in self.group:
                continue
            ds = self.group[path]
            if any(not isinstance(i, slice) and i >= n for i, n in zip(index, ds.shape[1:])):
                continue  # e.g. a reaction column added after these points
            avail = max(0, min(count, ds.shape[0] - file_first))
            block = read(ds, (slice(file_first, file_first + avail),) + tuple(index), whole)
            if out is None:
                out = np.full((stop - first,) + block.shape[1:], np.nan)
            out[at - first:at - first + avail] = block
        if out is None:
            if name not in self.group and "recent/" + name not in self.group:
                return None
            ds = self.group[name if name in self.group else "recent/" + name]
            shape = [len(range(*i.indices(n))) for i, n in
                     itertools.zip_longest(index, ds.shape[1:], fillvalue=slice(None))
                     if isinstance(i, slice)]
            out = np.full((stop - first, *shape), np.nan)
        return out

    def row(self, name, k, index=()):
        """Values of dataset `name` at time point k (see rows)."""
        values = self.rows(name, index, slice(k, k + 1))
        return None if values is None else values[0]

    def reactions(self, k, dof):
        """{node id: reaction} of DOF column `dof` (0..5) at time point k: the constrained DOFs."""
        if self.reaction_columns is None:  # format 1: dense (n_t, n_nodes, 6), NaN if free
            return None
        columns = [(n, c) for (n, d), c in self.reaction_columns.items() if d == dof]
        values = self.row("R", k) if columns else None
        if values is None:
            return {}
        # A column added after this point's row was written (R widens) is absent there.
        return {n: values[c] for n, c in columns if c < len(values)}

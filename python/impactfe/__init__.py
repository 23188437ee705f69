"""Read impactfe results files (<jobname>.h5) into pandas DataFrames.

    import impactfe
    r = impactfe.open("job.h5")
    r.history(node=43, item="UZ")

Schema: docs/results_file.md of the impactfe repository (format versions 1 and 2 are read).
"""
import bisect
import math

import h5py
import numpy as np
import pandas as pd

__all__ = ["open", "Results", "ResultsError", "NODAL_LABELS", "ENERGY_COLUMNS"]
__version__ = "0.1.0"

FORMAT_VERSIONS = (1, 2)

#: Nodal labels: dataset and DOF column.
NODAL_LABELS = {
    "UX": ("U", 0), "UY": ("U", 1), "UZ": ("U", 2),
    "ROTX": ("U", 3), "ROTY": ("U", 4), "ROTZ": ("U", 5),
    "VX": ("V", 0), "VY": ("V", 1), "VZ": ("V", 2),
    "AX": ("A", 0), "AY": ("A", 1), "AZ": ("A", 2),
    "FX": ("R", 0), "FY": ("R", 1), "FZ": ("R", 2),
    "MX": ("R", 3), "MY": ("R", 4), "MZ": ("R", 5),
}
ENERGY_COLUMNS = ["kinetic", "strain", "external_work", "gap_work", "dissipation", "plastic_work"]
DOF_COLUMNS = ["UX", "UY", "UZ", "ROTX", "ROTY", "ROTZ"]


class ResultsError(Exception):
    """A request the file cannot answer (unknown node, item, ...) or a damaged file."""


def open(path):  # noqa: A001 (the package's entry point, like h5py.File)
    """Opens a results file (also one that a running job is writing)."""
    return Results(path)


def _text(value):
    if isinstance(value, (bytes, np.bytes_)):
        return value.decode("utf-8", "replace").rstrip("\0")
    return str(value)


def same_time(a, b):
    """Two stored times are one time point when |a - b| <= 1e-12 max(1, |a|, |b|)."""
    return abs(a - b) <= 1e-12 * max(1.0, abs(a), abs(b))


def merge(per_analysis):
    """The merge rule of `impactfe post`: analyses in order, finite values only, a later
    analysis replaces an earlier value at the same time; sorted by time (stable)."""
    merged = []
    for points in per_analysis:
        if not points:
            continue
        later = sorted(t for t, _ in points)

        def in_later(t):
            i = bisect.bisect_left(later, t - 2e-12 * max(1.0, abs(t)))
            return i < len(later) and same_time(later[i], t)

        merged = [p for p in merged if not in_later(p[0])]
        merged.extend(points)
    return sorted(merged, key=lambda p: p[0])


class _Analysis:
    """One /analysis_<k> group: its times and where its rows live."""

    def __init__(self, group, index):
        self.group = group
        self.index = index
        self.kind = _text(group.attrs.get("kind", ""))
        self.status = _text(group.attrs.get("status", ""))
        self.description = _text(group.attrs.get("description", ""))
        self.times = group["time"][:] if "time" in group else np.zeros(0)
        # Format 2: points from first_row on are still in the staging datasets under recent/
        # (a job that is running or was killed); all points are in the main datasets otherwise.
        self.first_recent = len(self.times)
        if "recent" in group and "first_row" in group["recent"].attrs:
            self.first_recent = int(group["recent"].attrs["first_row"])
        self.reaction_columns = None
        if "reaction_dofs" in group:
            rd = group["reaction_dofs"][:]
            self.reaction_columns = {(int(n), int(d)): c for c, (n, d) in enumerate(rd)}

    def rows(self, name, index=()):
        """Values of dataset `name` at every time point, sliced by `index` along the other
        dimensions; NaN where absent."""
        n_t = len(self.times)
        out = None
        split = min(self.first_recent, n_t)
        parts = [(name, 0, 0, split), ("recent/" + name, split, 0, n_t - split)]
        for path, out_first, file_first, count in parts:
            if count <= 0 or path not in self.group:
                continue
            ds = self.group[path]
            avail = max(0, min(count, ds.shape[0] - file_first))
            block = ds[(slice(file_first, file_first + avail),) + tuple(index)]
            if out is None:
                out = np.full((n_t,) + block.shape[1:], np.nan)
            out[out_first:out_first + avail] = block
        if out is None:
            if name not in self.group and "recent/" + name not in self.group:
                return None
            ds = self.group[name]
            shape = np.empty(ds.shape[1:])[tuple(index)].shape
            out = np.full((n_t,) + shape, np.nan)
        return out


class Results:
    """An impactfe results file. Histories are pandas DataFrames indexed by time."""

    def __init__(self, path):
        self.path = str(path)
        try:
            # Without the HDF5 file lock: a running job holds it while it writes the file.
            self._f = h5py.File(self.path, "r", locking=False)
        except OSError as e:
            raise ResultsError(f"cannot open results file '{self.path}': {e}") from e
        f = self._f
        if _text(f.attrs.get("format", "")) != "impactfe-results":
            raise ResultsError(f"'{self.path}' is not an impactfe results file")
        self.format_version = int(f.attrs.get("format_version", 1))
        if self.format_version not in FORMAT_VERSIONS:
            raise ResultsError(f"'{self.path}' has format version {self.format_version}; this "
                               f"package reads versions {FORMAT_VERSIONS}")
        self.title = _text(f.attrs.get("title", ""))
        self.node_ids = f["model/node_ids"][:]
        self.node_coordinates = f["model/node_coordinates"][:]
        self.element_ids = f["model/element_ids"][:]
        self.element_type_names = [_text(x) for x in f["model/element_type_names"][:]]
        self._analyses = []
        k = 1
        while f"analysis_{k}" in f:
            self._analyses.append(_Analysis(f[f"analysis_{k}"], k))
            k += 1

    def close(self):
        self._f.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ---- the file's contents ---------------------------------------------------------------
    def analyses(self):
        """One row per analysis: index, kind, status, description, points, first/last time."""
        rows = []
        for a in self._analyses:
            rows.append({"analysis": a.index, "kind": a.kind, "status": a.status,
                         "description": a.description, "points": len(a.times),
                         "time_first": a.times[0] if len(a.times) else np.nan,
                         "time_last": a.times[-1] if len(a.times) else np.nan})
        return pd.DataFrame(rows).set_index("analysis") if rows else pd.DataFrame()

    def nodes(self):
        return pd.DataFrame(self.node_coordinates, index=pd.Index(self.node_ids, name="node"),
                            columns=["X", "Y", "Z"])

    def elements(self):
        f = self._f["model"]
        return pd.DataFrame({"type_name": self.element_type_names,
                             "type": f["element_types"][:], "mat": f["element_materials"][:],
                             "real": f["element_reals"][:]},
                            index=pd.Index(self.element_ids, name="element"))

    # ---- histories ---------------------------------------------------------------------------
    def _node_row(self, node):
        row = int(np.searchsorted(self.node_ids, node))
        if row >= len(self.node_ids) or self.node_ids[row] != node:
            raise ResultsError(f"node {node} is not in results file '{self.path}'")
        return row

    def _nodal_points(self, node, item):
        label = item.upper()
        if label not in NODAL_LABELS:
            raise ResultsError(f"unknown nodal result label '{item}' (expected "
                               + " ".join(NODAL_LABELS) + ")")
        dataset, col = NODAL_LABELS[label]
        row = self._node_row(node)
        per = []
        for a in self._analyses:
            if dataset == "R" and a.reaction_columns is not None:
                c = a.reaction_columns.get((int(node), col))
                values = None if c is None else a.rows("R", (c,))
            else:
                values = a.rows(dataset, (row, col))
            per.append(self._finite(a, values))
        return merge(per)

    def _element_points(self, element, item):
        if element not in set(self.element_ids.tolist()):
            raise ResultsError(f"element {element} is not in results file '{self.path}'")
        want = item.upper()
        per, found, available = [], False, set()
        for a in self._analyses:
            if "elements" not in a.group:
                continue
            for fam_name, fam in a.group["elements"].items():
                ids = list(fam["element_ids"][:])
                if element not in ids:
                    continue
                items = [_text(x) for x in fam.attrs["items"]]
                upper = [x.upper() for x in items]
                if want not in upper:
                    available.update(items)
                    continue
                found = True
                values = a.rows(f"elements/{fam_name}/values",
                                (ids.index(element), upper.index(want)))
                per.append(self._finite(a, values))
        if not found:
            if not available:
                raise ResultsError(f"no element results are stored for element {element}")
            raise ResultsError(f"element item '{item}' is not stored for element {element} "
                               f"(available: {' '.join(sorted(available))})")
        return merge(per)

    def _gap_points(self, gap):
        per, found = [], False
        for a in self._analyses:
            if "gap_forces" not in a.group or not 1 <= gap <= a.group["gap_forces"].shape[1]:
                continue
            found = True
            per.append(self._finite(a, a.rows("gap_forces", (gap - 1,))))
        if not found:
            raise ResultsError(f"gap {gap} is not stored in '{self.path}'")
        return merge(per)

    @staticmethod
    def _finite(a, values):
        if values is None:
            return []
        return [(float(t), float(v)) for t, v in zip(a.times, values) if math.isfinite(v)]

    def history(self, node=None, element=None, gap=None, item=None):
        """Time history as a DataFrame indexed by time: `node=43, item="UZ"` (or a list of
        items), `element=86, item="SEQV_TOP"`, `gap=1`. Columns are named like `impactfe post`
        (N43_UZ, E86_SEQV_TOP, GAP1); with several items the rows are the union of their times
        and a missing value is NaN."""
        if sum(x is not None for x in (node, element, gap)) != 1:
            raise ResultsError("give exactly one of node=, element=, gap=")
        items = [item] if isinstance(item, str) or item is None else list(item)
        columns = {}
        for it in items:
            if node is not None:
                if it is None:
                    raise ResultsError("give item= (UX..ROTZ, VX..VZ, AX..AZ, FX..MZ)")
                columns[f"N{node}_{it.upper()}"] = self._nodal_points(node, it)
            elif element is not None:
                if it is None:
                    raise ResultsError("give item= (SAXL, FORC, SEQV, ...)")
                columns[f"E{element}_{it.upper()}"] = self._element_points(element, it)
            else:
                columns[f"GAP{gap}"] = self._gap_points(gap)
        for name, pts in columns.items():
            # Not written (OUTRES) or never computed: an error, not an empty column.
            if not pts:
                raise ResultsError(f"{name}: no value is stored in '{self.path}' (not written "
                                   "by OUTRES, or not computed for this node / element)")
        frames = [pd.Series([v for _, v in pts], index=[t for t, _ in pts], name=name,
                            dtype=float) for name, pts in columns.items()]
        df = pd.concat(frames, axis=1) if len(frames) > 1 else frames[0].to_frame()
        df.index.name = "time"
        return df.sort_index(kind="stable")

    def energy(self):
        """Energy balance over time (full static and transient analyses): kinetic, strain,
        external_work, gap_work, dissipation, plastic_work and the numerical dissipation that
        remains."""
        parts = []
        for a in self._analyses:
            values = a.rows("energy")
            if values is None:
                continue
            # Files written before plastic_work existed have 5 columns.
            df = pd.DataFrame(values, columns=ENERGY_COLUMNS[:values.shape[1]], index=a.times)
            df.insert(0, "analysis", a.index)
            parts.append(df)
        if not parts:
            raise ResultsError(f"no energy balance is stored in '{self.path}'")
        df = pd.concat(parts)
        if "plastic_work" not in df:
            df["plastic_work"] = np.nan
        df["numerical"] = (df["external_work"] - df["kinetic"] - df["strain"] - df["gap_work"]
                           - df["dissipation"] - df["plastic_work"].fillna(0.0))
        df.index.name = "time"
        return df

    def _modal(self):
        for a in reversed(self._analyses):
            if "frequencies" in a.group:
                return a
        raise ResultsError(f"'{self.path}' holds no modal results")

    def frequencies(self):
        """Frequencies (Hz) of the last modal analysis, indexed by mode (1-based)."""
        f = self._modal().group["frequencies"][:]
        return pd.DataFrame({"frequency_hz": f},
                            index=pd.Index(np.arange(1, len(f) + 1), name="mode"))

    def mode_shape(self, mode):
        """Shape of mode `mode` (1-based) of the last modal analysis: UX .. ROTZ per node."""
        a = self._modal()
        n = a.group["frequencies"].shape[0]
        if not 1 <= mode <= n:
            raise ResultsError(f"mode {mode} does not exist (the file has modes 1..{n})")
        return pd.DataFrame(a.group["mode_shapes"][mode - 1], columns=DOF_COLUMNS,
                            index=pd.Index(self.node_ids, name="node"))

"""Read impactfe results files (<jobname>.h5) into pandas DataFrames. Example::

    import impactfe
    r = impactfe.open("out/helmet_full.h5")
    uz = r.history(node=43, item="UZ")            # one quantity over time
    seqv = r.field("SEQV_TOP", time=0.04)         # one quantity over the model at one time

Schema: docs/results_file.md of the impactfe repository (format versions 1 and 2 are read);
the package's guide: docs/python.md. Every failure is a ResultsError that says what the file
has, also for a damaged or truncated file.
"""
import bisect
import math

import numpy as np
import pandas as pd

from ._select import TIME_RTOL, data_sets, select
from ._storage import (FORMAT_VERSIONS, Analysis, Model, ResultsError, guarded, integer,
                       open_file, read, read_attribute_strings, text)

__all__ = ["open", "Results", "ResultsError", "NODAL_LABELS", "ENERGY_COLUMNS", "TIME_RTOL"]
__version__ = "0.2.0"

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
_DATASET_LABELS = {d: [lab for lab, (ds, _) in NODAL_LABELS.items() if ds == d] for d in "UVAR"}
#: Element types that only transmit contact: a node's part is that of a structural element.
_CONTACT_PREFIXES = ("CONTA", "TARGE")


def open(path):  # noqa: A001 (the package's entry point, like h5py.File)
    """Opens a results file (also one that a running job is writing)."""
    return Results(path)


def _labels(item, what):
    items = [item] if isinstance(item, str) else item
    try:
        items = list(items)
    except TypeError:
        items = None
    if not items or not all(isinstance(x, str) and x for x in items):
        raise ResultsError(f"give item= as a name or a list of names ({what}), not {item!r}")
    return [x.upper() for x in items]


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


class Results:
    """An impactfe results file: histories (one quantity over time) and fields (one quantity
    over the nodes or elements at one time) as pandas DataFrames."""

    def __init__(self, path):
        self.path = str(path)
        self._f = open_file(self.path)
        try:
            self._load()
        except BaseException:
            self._f.close()
            raise

    @guarded
    def _load(self):
        f = self._f
        if text(f.attrs.get("format", "")) != "impactfe-results":
            raise ResultsError(f"'{self.path}' is not an impactfe results file")
        self.format_version = int(f.attrs.get("format_version", 1))
        if self.format_version not in FORMAT_VERSIONS:
            raise ResultsError(f"'{self.path}' has format version {self.format_version}; this "
                               f"package reads versions {FORMAT_VERSIONS}")
        self.title = text(f.attrs.get("title", ""))
        self.units = text(f.attrs.get("units", ""))  # /UNITS label; "" when not given
        self._model = Model(f)
        self.node_ids = self._model.node_ids
        self.node_coordinates = self._model.node_coordinates
        self.element_ids = self._model.element_ids
        self.element_type_names = self._model.element_type_names
        self._analyses = []
        k = 1
        while f"analysis_{k}" in f:
            self._analyses.append(Analysis(f[f"analysis_{k}"], k, len(self.node_ids)))
            k += 1
        self._element_table = None
        self._node_table = None

    def close(self):
        self._f.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # ---- the file's contents ---------------------------------------------------------------
    @guarded
    def analyses(self):
        """One row per analysis: index, kind, status, description, points, first/last time."""
        rows = []
        for a in self._analyses:
            rows.append({"analysis": a.index, "kind": a.kind, "status": a.status,
                         "description": a.description, "points": len(a.times),
                         "time_first": a.times[0] if len(a.times) else np.nan,
                         "time_last": a.times[-1] if len(a.times) else np.nan})
        return pd.DataFrame(rows).set_index("analysis") if rows else pd.DataFrame()

    @guarded
    def nodes(self):
        """X, Y, Z (undeformed) and the part of each node: that of its lowest-numbered element
        that is not a contact or target element (of any element when it has only those; ""
        when it has none)."""
        if self._node_table is None:
            m = self._model
            df = pd.DataFrame(m.node_coordinates, columns=["X", "Y", "Z"],
                              index=pd.Index(m.node_ids, name="node"))
            part = np.full(len(m.node_ids), "", dtype=object)
            parts = self.elements()["part"].to_numpy()
            contact = np.array([n.startswith(_CONTACT_PREFIXES) for n in m.element_type_names],
                               dtype=bool)
            for chosen in (~contact, contact):  # structural elements first
                nodes = m.element_nodes[chosen]
                owner = np.repeat(np.flatnonzero(chosen), nodes.shape[1])
                nodes = nodes.ravel()
                keep = nodes != 0
                nodes, owner = nodes[keep], owner[keep]
                unique, first = np.unique(nodes, return_index=True)  # lowest element id first
                rows = m.node_rows(unique)
                free = part[rows] == ""
                part[rows[free]] = parts[owner[first[free]]]
            df["part"] = part
            self._node_table = df
        return self._node_table.copy()

    @guarded
    def elements(self):
        """Each element's type name, ET number, MAT, REAL, its part (the elements of one type,
        material and real set: "SHELL63 type 1 mat 1 real 1") and its centroid X, Y, Z
        (undeformed)."""
        if self._element_table is None:
            m = self._model
            df = pd.DataFrame({"type_name": m.element_type_names, "type": m.element_types,
                               "mat": m.element_materials, "real": m.element_reals},
                              index=pd.Index(m.element_ids, name="element"))
            df["part"] = [f"{n} type {t} mat {a} real {r}" for n, t, a, r in
                          zip(df["type_name"], df["type"], df["mat"], df["real"])]
            centroid = np.full((len(m.element_ids), 3), np.nan)
            nodes = m.element_nodes
            if nodes.size:
                used = nodes != 0
                rows = np.zeros(nodes.shape, dtype=np.int64)
                rows[used] = m.node_rows(nodes[used])
                xyz = m.node_coordinates[rows] * used[..., None]
                count = used.sum(axis=1)
                with np.errstate(invalid="ignore", divide="ignore"):
                    centroid = xyz.sum(axis=1) / count[:, None]
            df[["X", "Y", "Z"]] = centroid
            self._element_table = df
        return self._element_table.copy()

    @guarded
    def parts(self):
        """The parts (type name, ET, MAT, REAL) with their number of elements."""
        e = self.elements()
        return (e.groupby("part", sort=False)
                 .agg(type_name=("type_name", "first"), type=("type", "first"),
                      mat=("mat", "first"), real=("real", "first"), elements=("type", "size")))

    @guarded
    def sets(self):
        """POST1's data sets (SET,LIST): every stored time point of a static, transient or
        expansion analysis except a transient's initial state t = 0, and every mode; the
        numbers `field(..., set=n)` takes. A mode's time is NaN, its frequency_hz given."""
        rows, frequencies = [], {}
        for a, k, m in data_sets(self._analyses):
            if m and a.index not in frequencies:
                frequencies[a.index] = read(a.group["frequencies"])
            rows.append({"analysis": a.index, "kind": a.kind,
                         "time": np.nan if m else a.times[k],
                         "load_step": 1 if m else a.load_steps[k],
                         "substep": m if m else a.substeps[k], "mode": m or 0,
                         "frequency_hz": frequencies[a.index][m - 1] if m else np.nan})
        df = pd.DataFrame(rows, columns=["analysis", "kind", "time", "load_step", "substep",
                                         "mode", "frequency_hz"])
        df.index = pd.RangeIndex(1, len(df) + 1, name="set")
        return df

    @guarded
    def items(self):
        """What the file stores: {"nodal": [labels], element type name: [items], ...}."""
        out = {"nodal": []}
        datasets = {d for a in self._analyses for d in "UVAR" if d in a.group
                    or "recent/" + d in a.group}
        if any(a.n_modes for a in self._analyses):
            datasets.add("U")
        out["nodal"] = [lab for d in "UVAR" if d in datasets for lab in _DATASET_LABELS[d]]
        names = np.array(self.element_type_names, dtype=object)
        for a in self._analyses:
            for fam in a.families:
                rows = self._model.element_rows(fam.element_ids)
                for type_name in pd.unique(names[rows]):
                    have = out.setdefault(type_name, [])
                    have.extend(x for x in fam.items if x not in have)
        return out

    def _available(self):
        return "; ".join(f"{k}: {' '.join(v)}" for k, v in self.items().items() if v)

    # ---- histories ---------------------------------------------------------------------------
    def _node_row(self, node):
        node = integer(node, "node")
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
        element = integer(element, "element")
        if element not in set(self.element_ids.tolist()):
            raise ResultsError(f"element {element} is not in results file '{self.path}'")
        want = item.upper()
        per, found, available = [], False, set()
        for a in self._analyses:
            for fam in a.families:
                if element not in fam.row:
                    continue
                if want not in fam.upper:
                    available.update(fam.items)
                    continue
                found = True
                values = a.rows(f"elements/{fam.name}/values",
                                (fam.row[element], fam.upper.index(want)))
                per.append(self._finite(a, values))
        if not found:
            if not available:
                raise ResultsError(f"no element results are stored for element {element}")
            raise ResultsError(f"element item '{item}' is not stored for element {element} "
                               f"(available: {' '.join(sorted(available))})")
        return merge(per)

    def _gap_points(self, gap):
        gap = integer(gap, "gap")
        per, found = [], False
        for a in self._analyses:
            if "gap_forces" not in a.group or not 1 <= gap <= a.group["gap_forces"].shape[1]:
                continue
            found = True
            per.append(self._finite(a, a.rows("gap_forces", (gap - 1,))))
        if not found:
            raise ResultsError(f"gap {gap} is not stored in '{self.path}' (GP gap conditions of "
                               "reduced and mode-superposition transients; the force of a "
                               "gap element such as COMBIN40 is its element item FORC)")
        return merge(per)

    def _triple_points(self, dataset, index, item, items, missing):
        """Series of column 3 (index - 1) + items[item] of a dataset of three values per entity
        (contact_forces, part_energies)."""
        column = items.get(str(item).upper())
        if column is None:
            raise ResultsError(f"'{item}' is not one of {', '.join(items)}")
        per, found = [], False
        for a in self._analyses:
            if dataset not in a.group or not 1 <= index <= a.group[dataset].shape[1] // 3:
                continue
            found = True
            per.append(self._finite(a, a.rows(dataset, (3 * (index - 1) + column,))))
        if not found:
            raise ResultsError(f"{missing} in '{self.path}'")
        return merge(per)

    def _contact_points(self, entity, component):
        entity = integer(entity, "contact")
        return self._triple_points("contact_forces", entity, component,
                                   {"FX": 0, "FY": 1, "FZ": 2},
                                   f"contact {entity} is not stored (explicit runs store the "
                                   "force of each EDCGEN contact)")

    def _part_points(self, part, item):
        part = integer(part, "part")
        return self._triple_points("part_energies", part, item, {"KE": 0, "IE": 1, "HE": 2},
                                   f"part {part} has no energies stored (explicit runs store "
                                   "them: KE kinetic, IE internal, HE hourglass)")

    @staticmethod
    def _finite(a, values):
        if values is None:
            return []
        return [(float(t), float(v)) for t, v in zip(a.times, values) if math.isfinite(v)]

    @guarded
    def history(self, node=None, element=None, gap=None, item=None, contact=None,
                part=None):
        """Time history as a DataFrame indexed by time: `node=43, item="UZ"` (or a list of
        items), `element=86, item="SEQV_TOP"`, `gap=1`, `contact=1, item="FZ"` (the force on
        the contact surface of explicit contact 1), `part=2, item="KE"` (KE, IE, HE: the
        kinetic, internal, hourglass energy of part 2 of an explicit run). Columns are named
        like `impactfe post` (N43_UZ, E86_SEQV_TOP, GAP1, CONTACT1_FZ, PART2_KE); with several
        items the rows are the union of their times and a missing value is NaN."""
        if sum(x is not None for x in (node, element, gap, contact, part)) != 1:
            raise ResultsError("give exactly one of node=, element=, gap=, contact=, part=")
        if gap is not None:
            items = [None]
        elif item is None:
            raise ResultsError("give item= (" + ("UX..ROTZ, VX..VZ, AX..AZ, FX..MZ"
                                                 if node is not None else "FX, FY, FZ"
                                                 if contact is not None else "KE, IE, HE"
                                                 if part is not None else
                                                 "SAXL, FORC, SEQV, ...") + ")")
        else:
            items = _labels(item, "UX, SEQV, ...")
        columns = {}
        for it in items:
            if node is not None:
                columns[f"N{node}_{it}"] = self._nodal_points(node, it)
            elif element is not None:
                columns[f"E{element}_{it}"] = self._element_points(element, it)
            elif contact is not None:
                columns[f"CONTACT{contact}_{it}"] = self._contact_points(contact, it)
            elif part is not None:
                columns[f"PART{part}_{it}"] = self._part_points(part, it)
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

    # ---- fields --------------------------------------------------------------------------------
    @guarded
    def field(self, item, time=None, *, set=None, analysis=None):  # noqa: A002 (POST1's word)
        """One or more quantities over the whole model at one stored point, as a DataFrame.

        `item`: a nodal label (UX..ROTZ, VX..VZ, AX..AZ, reactions FX..MZ) or an element item
        the file stores (SEQV_TOP, SEQV, SAXL, FORC, STAT, ...; `items()` lists them), or a
        list of either kind. Nodal: one row per node (reactions: per node with that DOF
        constrained), columns X Y Z part and the labels. Element: one row per element that has
        the item, columns X Y Z (centroid) part type_name type mat real and the items.

        The point: `time=t` selects the time point stored at t (|t_s - t| <= TIME_RTOL
        max(|t|, |t_s|); t = 0 of a transient is its initial state); at a time stored by
        several analyses their values are merged as in history() (the later analysis wins
        where it has a value) unless `analysis=k` restricts it to one. `set=n` selects POST1's
        data set n (`sets()`; a mode of a modal analysis is a set). Neither: the last set
        (POST1 SET,LAST) of the file, or of analysis k. A time that is not stored is an error
        naming the stored times around it: values are never interpolated.
        NaN: a value not stored at that point (a DOF the node does not have, OUTRES). The
        frame's attrs hold the point: time, set, point (a description)."""
        labels = _labels(item, "UX, SEQV, ...")
        nodal = [lab in NODAL_LABELS for lab in labels]
        if any(nodal) and not all(nodal):
            raise ResultsError("give nodal labels or element items in one field(), not both")
        if not all(nodal):
            self._check_element_items(labels)
        point = select(self._analyses, self.path, time, set, analysis)
        df = self._nodal_field(labels, point) if all(nodal) else \
            self._element_field(labels, point)
        df.attrs.update(time=point.time, set=point.set_number, point=point.describe())
        return df

    def _check_element_items(self, labels):
        have = {x.upper() for a in self._analyses for fam in a.families for x in fam.items}
        for lab in labels:
            if lab not in have:
                raise ResultsError(f"'{lab}' is neither a nodal label nor an element item stored "
                                   f"in '{self.path}' (it has {self._available()})")

    def _nodal_values(self, a, k, dataset, col):
        if dataset == "R" and a.reaction_columns is not None:
            values = np.full(len(self.node_ids), np.nan)
            by_node = a.reactions(k, col)
            if by_node:
                values[self._model.node_rows(list(by_node))] = list(by_node.values())
            return values
        return a.row(dataset, k, (slice(None), col))

    def _nodal_field(self, labels, point):
        df = self.nodes()
        for lab in labels:
            dataset, col = NODAL_LABELS[lab]
            values = None
            if point.mode is not None:
                if dataset != "U":
                    raise ResultsError(f"{point.describe()} holds mode shapes only (UX..ROTZ), "
                                       f"not {lab}")
                a, m = point.mode
                values = read(a.group["mode_shapes"], (m - 1, slice(None), col))
            for a, k in point.sources:
                v = self._nodal_values(a, k, dataset, col)
                if v is not None:
                    values = v if values is None else np.where(np.isfinite(v), v, values)
            if values is None or not np.isfinite(values).any():
                stored = [a.index for a in self._analyses if dataset in a.group
                          or "recent/" + dataset in a.group]
                raise ResultsError(
                    f"{lab} has no value at {point.describe()} in '{self.path}': "
                    + (f"it is stored in analyses {stored} but was not written at this point "
                       "(OUTRES)" if stored else f"the file has no {lab} (it has "
                       f"{self._available()})"))
            df[lab] = values
        if all(NODAL_LABELS[lab][0] == "R" for lab in labels):
            df = df[np.isfinite(df[labels].to_numpy()).any(axis=1)]  # the constrained nodes
        return df

    def _element_field(self, labels, point):
        if point.mode is not None:
            raise ResultsError(f"{point.describe()} holds mode shapes only (UX..ROTZ), no "
                               "element results")
        values = {lab: pd.Series(dtype=float) for lab in labels}
        for a, k in point.sources:
            for fam in a.families:
                mine = [lab for lab in labels if lab in fam.upper]
                if not mine:
                    continue
                block = a.row(f"elements/{fam.name}/values", k)
                for lab in mine:
                    column = pd.Series(block[:, fam.upper.index(lab)], index=fam.element_ids)
                    # A later analysis's finite value wins (the merge rule of history()).
                    values[lab] = column if values[lab].empty else \
                        column.combine_first(values[lab])
        for lab, column in values.items():
            if not np.isfinite(column.to_numpy()).any():
                stored = sorted({a.index for a in self._analyses for fam in a.families
                                 if lab in fam.upper})
                raise ResultsError(
                    f"{lab} has no value at {point.describe()} in '{self.path}': it is stored in "
                    f"analyses {stored}" + (" but was not written at this point (OUTRES)"
                                            if len(column) else ""))
        ids = pd.Index(np.unique(np.concatenate([c.index.to_numpy() for c in values.values()])))
        df = self.elements().loc[ids, ["X", "Y", "Z", "part", "type_name", "type", "mat",
                                       "real"]]
        for lab in labels:
            df[lab] = values[lab].reindex(ids).to_numpy()
        return df

    # ---- energy and modes --------------------------------------------------------------------
    @guarded
    def energy(self):
        """Energy balance over time (full static and transient analyses): kinetic, strain,
        external_work, gap_work, dissipation, plastic_work, initial_kinetic (the kinetic
        energy of the initial velocities, IC, at t = 0: energy put in like external work) and
        the numerical dissipation that remains,
        numerical = initial_kinetic + external_work - kinetic - strain - gap_work
                    - dissipation - plastic_work,
        the run summary's "numerical dissipation" (0 at t = 0)."""
        parts, run_t0 = [], None
        for a in self._analyses:
            values = a.rows("energy")
            if values is None:
                continue
            ds = a.group["energy" if "energy" in a.group else "recent/energy"]
            columns = (read_attribute_strings(ds, "columns") if "columns" in ds.attrs
                       else ENERGY_COLUMNS[:values.shape[1]])
            if len(columns) != values.shape[1]:
                raise ValueError(f"{ds.name} has {values.shape[1]} columns and "
                                 f"{len(columns)} names")
            df = pd.DataFrame(values, columns=columns, index=a.times)
            df.insert(0, "analysis", a.index)
            if "initial_kinetic" not in df:
                df["initial_kinetic"], run_t0 = self._initial_kinetic(a, df, run_t0)
            parts.append(df)
        if not parts:
            raise ResultsError(f"no energy balance is stored in '{self.path}'")
        df = pd.concat(parts)
        for name in ENERGY_COLUMNS:
            if name not in df:
                df[name] = np.nan  # files written before plastic_work existed: 5 columns
        df = df[["analysis", *ENERGY_COLUMNS, "initial_kinetic",
                 *[c for c in df if c not in ENERGY_COLUMNS + ["analysis", "initial_kinetic"]]]]
        df["numerical"] = (df["initial_kinetic"] + df["external_work"] - df["kinetic"]
                           - df["strain"] - df["gap_work"] - df["dissipation"]
                           - df["plastic_work"].fillna(0.0))
        df.index.name = "time"
        return df

    @staticmethod
    def _initial_kinetic(a, df, run_t0):
        """(T0 of analysis a, T0 of the run a later restart continues). A transient stores its
        initial state (load step 0, t = 0) first, where the kinetic energy is that of the
        initial velocities; a transient without one continues an earlier run from a restart
        point (ANTYPE,,RESTART adds an analysis) and carries that run's T0: unknown (NaN) when
        the file does not hold it. Static analyses start at rest."""
        row = a.initial_row()
        if row is not None:
            t0 = float(df["kinetic"].iloc[row]) if "kinetic" in df else np.nan
            t0 = 0.0 if not math.isfinite(t0) and a.kind != "transient" else t0
            return t0, t0
        if a.kind == "transient":
            return (np.nan if run_t0 is None else run_t0), run_t0
        return 0.0, run_t0

    def _modal(self):
        for a in reversed(self._analyses):
            if a.n_modes:
                return a
        raise ResultsError(f"'{self.path}' holds no modal results")

    @guarded
    def frequencies(self):
        """Frequencies (Hz) of the last modal analysis, indexed by mode (1-based)."""
        f = read(self._modal().group["frequencies"])
        return pd.DataFrame({"frequency_hz": f},
                            index=pd.Index(np.arange(1, len(f) + 1), name="mode"))

    @guarded
    def mode_shape(self, mode):
        """Shape of mode `mode` (1-based) of the last modal analysis: UX .. ROTZ per node."""
        a = self._modal()
        mode = integer(mode, "mode")
        if not 1 <= mode <= a.n_modes:
            raise ResultsError(f"mode {mode} does not exist (the file has modes 1..{a.n_modes})")
        return pd.DataFrame(read(a.group["mode_shapes"], (mode - 1,)), columns=DOF_COLUMNS,
                            index=pd.Index(self.node_ids, name="node"))

"""Which stored point a field is read at: POST1's data sets (src/results/result_sets.cpp) and
stored times. Never an interpolation: a time that is not stored is an error that names the
stored times around it."""
import math

import numpy as np

from ._storage import ResultsError, integer, read

#: A requested time selects a stored time t_s when |t_s - t| <= TIME_RTOL max(|t|, |t_s|): the
#: round-off of a time typed in decimal or summed from steps, never a neighbouring point.
TIME_RTOL = 1e-9


class Point:
    """The chosen point: its time (the frequency of a mode), the (analysis, row) pairs to read
    in merge order (a later analysis wins where it has a value), or a mode (analysis, mode)."""

    def __init__(self, time, sources=(), mode=None, set_number=None):
        self.time = time
        self.sources = list(sources)
        self.mode = mode
        self.set_number = set_number

    def describe(self):
        if self.mode is not None:
            a, m = self.mode
            return f"mode {m} of analysis {a.index} ({self.time:.6g} Hz)"
        a, k = self.sources[-1]
        where = f"set {self.set_number}, " if self.set_number else ""
        return (f"t = {self.time:.10g} ({where}load step {a.load_steps[k]}, substep "
                f"{a.substeps[k]}, analysis {'+'.join(str(s.index) for s, _ in self.sources)})")


def data_sets(analyses):
    """POST1's numbered data sets in file order: every stored time point of a static, transient
    or expansion analysis except the initial state t = 0 of a transient, every mode of a modal
    analysis; a reduced transient's points only when no expansion pass follows it. Each set is
    (analysis, row, mode): row None for a mode, mode None for a time point."""
    sets = []
    for i, a in enumerate(analyses):
        if a.kind == "substructure":
            continue
        if a.kind == "modal":
            sets.extend((a, None, m) for m in range(1, a.n_modes + 1))
            continue
        if a.kind == "reduced_transient" and any(b.kind == "expansion" for b in analyses[i + 1:]):
            continue
        sets.extend((a, k, None) for k in range(len(a.times)) if a.load_steps[k] != 0)
    return sets


def _time_analyses(analyses):
    return [a for a in analyses if a.kind not in ("modal", "substructure") and len(a.times)]


def _stored_rows(a, t):
    scale = np.maximum(abs(t), np.abs(a.times))
    return np.flatnonzero(np.abs(a.times - t) <= TIME_RTOL * scale)


def _not_stored(analyses, t, path, frequencies):
    times = np.unique(np.concatenate([a.times for a in analyses])) if analyses else np.zeros(0)
    if len(times) == 0:
        return ResultsError(f"'{path}' stores no time point{frequencies}")
    below, above = times[times < t], times[times > t]
    near = [f"{x:.10g}" for x in (below[-1:].tolist() + above[:1].tolist())]
    return ResultsError(
        f"time {t:.10g} is not a stored time point (no interpolation): the nearest stored "
        f"{'times are' if len(near) > 1 else 'time is'} {' and '.join(near)}; stored: "
        f"{len(times)} time points from {times[0]:.10g} to {times[-1]:.10g} (r.sets() lists "
        f"them){frequencies}")


def select(analyses, path, time=None, set=None, analysis=None):  # noqa: A002 (POST1's word)
    """The Point of field(): `set=n` (POST1 SET,,,,,,,n; r.sets() lists them) alone; or
    `time=t` (a stored time; with analysis=k only that analysis, else every analysis storing t,
    merged); or neither: the last set (POST1 SET,LAST) of the file or of analysis k."""
    sets = data_sets(analyses)
    if analysis is not None:
        k = integer(analysis, "analysis")
        if not 1 <= k <= len(analyses):
            raise ResultsError(f"analysis {k} does not exist ('{path}' has analyses "
                               f"1..{len(analyses)})")
        chosen = [analyses[k - 1]]
    else:
        chosen = analyses
    if set is not None:
        if time is not None or analysis is not None:
            raise ResultsError("give set= alone: a set is one stored point of one analysis")
        n = integer(set, "set")
        if not 1 <= n <= len(sets):
            raise ResultsError(f"set {n} does not exist ('{path}' has "
                               + (f"sets 1..{len(sets)}: r.sets() lists them)" if sets
                                  else "no data set)"))
        return _point_of_set(sets[n - 1], n)
    if time is None:
        mine = [s for s in sets if s[0] in chosen]
        if not mine:
            where = f"analysis {chosen[0].index} of " if analysis is not None else ""
            raise ResultsError(f"{where}'{path}' holds no data set (no stored time point or mode)")
        return _point_of_set(mine[-1], sets.index(mine[-1]) + 1)
    try:
        t = float(time)
    except (TypeError, ValueError):
        raise ResultsError(f"time must be a number, not {time!r}") from None
    if not math.isfinite(t):
        raise ResultsError(f"time must be finite, not {time!r}")
    timed = _time_analyses(chosen)
    sources = []
    for a in timed:
        rows = _stored_rows(a, t)
        if len(rows):
            sources.append((a, int(rows[-1])))  # the last point stored at t in the analysis
    if not sources:
        modal = any(a.kind == "modal" for a in chosen)
        raise _not_stored(timed, t, path,
                          "; modes are selected by set= (r.sets())" if modal else "")
    a, k = sources[-1]
    number = next((i + 1 for i, s in enumerate(sets) if s[0] is a and s[1] == k), None)
    return Point(float(a.times[k]), sources, set_number=number)


def _point_of_set(s, number):
    a, k, m = s
    if m is not None:
        frequency = read(a.group["frequencies"], (slice(m - 1, m),))[0]
        return Point(float(frequency), mode=(a, m), set_number=number)
    return Point(float(a.times[k]), [(a, k)], set_number=number)

"""Everything the Python package gives for one results file, as one text, and a corruption
driver that compares copies of a file with it (run in a child process by
test_package_integrity.py, so that a crash inside HDF5 is seen as one, not as pytest dying).

    python3 results_probe.py FILE OUT_DIR SEED TRIALS
prints one line per corrupted copy: `offset outcome [detail]`, outcome one of same (harmless),
reported (a ResultsError), different (other values, no error), error (another exception)."""
import os
import shutil
import sys
import random
import warnings

import impactfe


def _requests(r):
    """(method, keyword arguments) of every call: the model tables, energy, modes, the history
    of every node and element, the fields of every label and item at five sets. The labels of
    one dataset (UX..ROTZ, VX..VZ, ...) and the items of one element type are asked together."""
    out = [(name, {}) for name in ("analyses", "nodes", "elements", "parts", "sets", "items",
                                   "energy", "frequencies")]
    out += [("mode_shape", {"mode": m}) for m in (1, 2)]
    nodal = [[lab for lab, (d, _) in impactfe.NODAL_LABELS.items() if d == ds] for ds in "UVAR"]
    element = list(r.items().values())[1:]
    out += [("history", {"node": int(n), "item": labels}) for n in r.node_ids for labels in nodal]
    out += [("history", {"element": int(e), "item": items})
            for e in r.element_ids for items in element]
    out += [("history", {"gap": 1})]
    n_sets = len(r.sets())
    for s in sorted({1, 2, 3, n_sets // 2, n_sets}):
        out += [("field", {"item": labels, "set": s}) for labels in nodal + element]
    out += [("field", {"item": "UX"}), ("field", {"item": "UX", "time": 0.0})]
    return out


def _answers(r, name, kwargs):
    try:
        getattr(r, name)(**kwargs)
        return True
    except impactfe.ResultsError:
        return False


def valid_requests(path):
    """The requests the intact file answers; of a list of labels or items, the ones it answers
    one by one, asked together."""
    valid = []
    with impactfe.open(path) as r:
        for name, kwargs in _requests(r):
            if isinstance(kwargs.get("item"), list):
                items = [i for i in kwargs["item"] if _answers(r, name, {**kwargs, "item": i})]
                if items:
                    valid.append((name, {**kwargs, "item": items}))
            elif _answers(r, name, kwargs):
                valid.append((name, kwargs))
    return valid


def everything(path, requests):
    """All the answers for `path` as one text (the file's own path left out)."""
    texts = []
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning on a damaged file counts as an error
        with impactfe.open(path) as r:
            texts.append(f"{r.title} {r.format_version}")
            for request in requests:
                answer = getattr(r, request[0])(**request[1])
                texts.append(f"{request}\n{getattr(answer, 'to_string', answer.__repr__)()}")
    return "\n".join(texts).replace(path, "FILE")


def main(path, out_dir, seed, trials):
    requests = valid_requests(path)
    copy = os.path.join(out_dir, "copy.h5")
    shutil.copy(path, copy)
    reference = everything(copy, requests)
    size = os.path.getsize(path)
    rng = random.Random(seed)
    print(f"requests {len(requests)}", flush=True)
    for _ in range(trials):
        at = rng.randrange(0, size - 8)
        garbage = bytes(rng.randrange(256) for _ in range(8))
        shutil.copy(path, copy)
        with open(copy, "r+b") as f:
            f.seek(at)
            f.write(garbage)
        print(f"{at} start", flush=True)  # the last line when the child crashes
        try:
            outcome = "same" if everything(copy, requests) == reference else "different"
            detail = ""
        except impactfe.ResultsError as e:
            outcome, detail = "reported", str(e).splitlines()[0]
        except BaseException as e:  # noqa: B902 (what the test looks for)
            outcome, detail = "error", f"{type(e).__name__}: {e}"
        print(f"{at} {outcome} {detail}", flush=True)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4]))

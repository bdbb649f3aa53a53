"""Every single-run scene's answers, kept and compared: the check that a faster loop changed no answer.

``--save FILE`` simulates every single-run scene (``scenarios/*.yaml`` without a ``sweep:``, every Modelica
example and the stick-slip chain of ``single_run_cost.py``) and keeps, per scene, its output grid's rows of
every series, every event's time and kind, its exact instants and its summary values (``.npz``).
``--against FILE`` simulates them again and compares, scene by scene:

- events and instants: the same count and kinds, their times within ``--event-tol`` s (1e-9);
- series on the output grid: within ``--series-tol`` (1e-8) of the series' range (its max less its min,
  at least 1e-300) in the old run, the grid being the same times;
- summary values: within 1e-8 of their magnitude (at least 1e-12), NaN where NaN;
- no series, summary value, event or instant field the old runs did not have (the file's layout kept).

It prints a row per scene (the worst event time difference, the worst series difference over its range
and the series it is in, the worst summary value) and exits 1 if any is out of tolerance.

    python benchmarks/answers.py --save /tmp/before.npz
    python benchmarks/answers.py --against /tmp/before.npz

``--set KEY=VALUE`` runs every scene so (``--set simulation.rtol=1e-12 --set simulation.atol=1e-14``: a
reference far finer than the runs' own tolerance), and ``--stored FILE`` compares answers kept in FILE
instead of simulating: so two kept runs are each compared with a finer reference, to tell a change within
the runs' own accuracy (both as far from the reference) from one beyond it.

    python benchmarks/answers.py --save /tmp/reference.npz --set simulation.rtol=1e-12 --set simulation.atol=1e-14
    python benchmarks/answers.py --against /tmp/reference.npz --stored /tmp/before.npz
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from single_run_cost import scene_paths  # noqa: E402


def answers(path: Path, overrides=()) -> dict[str, np.ndarray]:
    """A scene's answers, flat: ``series/NAME`` on the grid, ``events/time``, ``events/kind``, ``instants/...``,
    ``values/NAME``."""
    from hoistsim import load_scenario, simulate

    result = simulate(load_scenario(path, overrides=list(overrides)))
    grid = result.grid_rows()
    out = {f"series/{name}": np.asarray(values, dtype=float)[grid] for name, values in result.series.items()}
    out["series/time"] = np.asarray(result.time, dtype=float)[grid]
    for name, values in (result.instants or {}).items():
        out[f"instants/{name}"] = np.asarray(values)
    for name, values in result.events.items():
        out[f"events/{name}"] = np.asarray(values)
    for name, value in result.values.items():
        if np.ndim(value) == 0 and np.issubdtype(np.asarray(value).dtype, np.number):
            out[f"values/{name}"] = np.asarray(value, dtype=float)
    return out


def compare(old: dict, new: dict, event_tol: float, series_tol: float) -> tuple[bool, str]:
    """Whether ``new`` agrees with ``old``, and a row saying by how much."""
    problems = []
    worst_time = 0.0
    for key in sorted(k for k in old if k.startswith(("events/", "instants/"))):
        a, b = old[key], new.get(key)
        if b is None or a.shape != b.shape:
            problems.append(f"{key}: {None if b is None else b.shape} against {a.shape}")
            continue
        if key.endswith("/time"):
            worst_time = max(worst_time, float(np.max(np.abs(a - b), initial=0.0)))
        elif a.dtype.kind in "fc":
            continue  # a value at an instant (a torque margin): a series' check, not a count's
        elif not np.array_equal(a, b):
            problems.append(f"{key} differs")
    if worst_time > event_tol:
        problems.append(f"an event {worst_time:.1e} s off")
    worst_series, where = 0.0, ""
    for key in sorted(k for k in old if k.startswith("series/")):
        a, b = old[key], new.get(key)
        if b is None or a.shape != b.shape:
            problems.append(f"{key}: {None if b is None else b.shape} against {a.shape}")
            continue
        finite = np.isfinite(a)
        if not np.array_equal(finite, np.isfinite(b)):
            problems.append(f"{key}: finite in one, not the other")
            continue
        if not finite.any():
            continue
        span = max(float(np.ptp(a[finite])), 1e-300)
        off = float(np.max(np.abs(a[finite] - b[finite]))) / span
        if off > worst_series:
            worst_series, where = off, key[len("series/"):]
    if worst_series > series_tol:
        problems.append(f"{where} {worst_series:.1e} of its range")
    worst_value = 0.0
    for key in sorted(k for k in old if k.startswith("values/")):
        a, b = float(old[key]), float(new.get(key, np.nan))
        if np.isnan(a) and np.isnan(b):
            continue
        off = abs(a - b) / max(abs(a), 1e-12)
        worst_value = max(worst_value, off if np.isfinite(off) else np.inf)
    if worst_value > series_tol:
        problems.append(f"a summary value {worst_value:.1e} off")
    added = sorted(k for k in new if k not in old and k.startswith(("series/", "values/", "events/", "instants/")))
    if added:  # the file's layout has grown: an output the old runs did not write
        problems.append(f"new: {', '.join(added[:4])}{', ...' if len(added) > 4 else ''}")
    row = f"events {worst_time:8.1e} s   series {worst_series:8.1e} ({where or '-'})   values {worst_value:8.1e}"
    return not problems, row + ("   " + "; ".join(problems) if problems else "")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--save", type=Path, help="keep every scene's answers here (.npz)")
    parser.add_argument("--against", type=Path, help="compare every scene with the answers kept here")
    parser.add_argument("--scenes", nargs="*", default=None, help="names (a file's stem; modelica/NAME)")
    parser.add_argument("--set", action="append", default=[], help="KEY=VALUE for every scene's run")
    parser.add_argument("--stored", type=Path, help="compare the answers kept here, not a new run")
    parser.add_argument("--event-tol", type=float, default=1e-9)
    parser.add_argument("--series-tol", type=float, default=1e-8)
    options = parser.parse_args()
    if (options.save is None) == (options.against is None):
        parser.error("give one of --save FILE and --against FILE")
    with tempfile.TemporaryDirectory() as folder:
        paths = scene_paths(Path(folder))
        if options.scenes:
            paths = {name: path for name, path in paths.items()
                     if name in options.scenes or name.split("/")[-1] in options.scenes}
        if options.save:
            kept = {}
            for name, path in paths.items():
                kept.update({f"{name}|{key}": value for key, value in answers(path, options.set).items()})
                print(f"{name}: kept", flush=True)
            np.savez_compressed(options.save, **kept)
            return
        stored = np.load(options.against, allow_pickle=True)  # kinds and names are strings
        other = None if options.stored is None else np.load(options.stored, allow_pickle=True)

        def kept(store, name):
            return {key.split("|", 1)[1]: store[key] for key in store.files if key.startswith(name + "|")}
        ok = True
        for name, path in paths.items():
            old = kept(stored, name)
            if not old:
                print(f"{name:42} not kept before")
                continue
            new = answers(path, options.set) if other is None else kept(other, name)
            agrees, row = compare(old, new, options.event_tol, options.series_tol)
            ok &= agrees
            print(f"{name:42} {'ok  ' if agrees else 'OFF '} {row}", flush=True)
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()

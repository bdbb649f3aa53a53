"""Modelica's published reference trajectories (tests/data/modelica/, from modelica/MAP-LIB_ReferenceResults; its
source in SOURCE.md) and how far a run is from them: what the tests of the Modelica examples share."""

from __future__ import annotations

import csv
import gzip

import numpy as np
from helpers import TESTS

DATA = TESTS / "data" / "modelica"


def reference(example: str) -> dict:
    """The example's reference trajectories: signal -> its column (``time`` among them); ``<Example>.csv``, or
    ``.csv.gz`` for the larger ones (the same file, compressed)."""
    plain = DATA / f"{example}.csv"
    with (plain.open() if plain.exists() else gzip.open(DATA / f"{example}.csv.gz", "rt")) as f:
        rows = list(csv.reader(f))
    table = np.asarray([[float(v) for v in row] for row in rows[1:]])
    # (the time's header is "time", or "Time" in some files)
    return {"time" if name == "Time" else name: table[:, i] for i, name in enumerate(rows[0])}


def events(times):
    """The reference's event instants: the times it repeats."""
    return np.unique(times[1:][np.diff(times) == 0.0])


def deviations(run, example: str, ours: dict, until: float = np.inf) -> dict:
    """Each comparison signal's worst deviation from the reference, over its range (:func:`_range`), at every
    reference row more than 1 ms from a reference event (``ours``: signal -> our series on the run's rows), before
    ``until`` (s)."""
    table = reference(example)
    times = table["time"]
    instants = events(times)
    far = (np.min(np.abs(times[:, None] - instants[None, :]), axis=1) > 1e-3 if len(instants)
           else np.ones(times.shape, bool)) & (times < until)
    return {signal: float(np.max(np.abs(np.interp(times, run.time, series) - table[signal])[far])
                          / _range(table[signal])) for signal, series in ours.items()}


def _range(values):
    """A signal's range; one that never moves (a mass at rest throughout), its magnitude, at least 1 of its unit."""
    spread = np.ptp(values)
    return spread if spread > 0.0 else max(float(np.max(np.abs(values))), 1.0)

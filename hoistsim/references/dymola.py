"""Dymola's published trajectories of Modelica's examples, and how far a run is from them: the reading and the
measure that the tests of the examples and the documentation's gallery share.

The trajectories are modelica/MAP-LIB_ReferenceResults' (the repository keeps them under tests/data/modelica/,
their source in its SOURCE.md): a CSV an example, ``<Example>.csv`` or, for the larger ones, ``.csv.gz``, its
header the signals' Modelica names.  A run is held to each comparison signal at every reference row more than
1 ms from a reference event (a time the file repeats: there the two solvers' instants differ by their
tolerances, and a signal that jumps is far from itself on either side), as a fraction of the signal's range.
What each example compares, from which of a run's series, is :mod:`.modelica_signals`.
"""

from __future__ import annotations

import csv
import gzip
from pathlib import Path

import numpy as np

EVENT_MARGIN = 1e-3  # s: reference rows this close to one of its events are not compared


def reference_file(folder, example: str) -> Path:
    """The file of ``example``'s trajectories in ``folder``: ``<example>.csv``, else ``<example>.csv.gz``."""
    plain = Path(folder) / f"{example}.csv"
    return plain if plain.exists() else Path(folder) / f"{example}.csv.gz"


def read_reference(folder, example: str) -> dict[str, np.ndarray]:
    """The example's reference trajectories: signal -> its column (``time`` among them)."""
    path = reference_file(folder, example)
    with (gzip.open(path, "rt") if path.suffix == ".gz" else path.open()) as f:
        rows = list(csv.reader(f))
    table = np.asarray([[float(v) for v in row] for row in rows[1:]])
    # (the time's header is "time", or "Time" in some files)
    return {"time" if name == "Time" else name: table[:, i] for i, name in enumerate(rows[0])}


def events(times) -> np.ndarray:
    """The reference's event instants: the times it repeats."""
    return np.unique(times[1:][np.diff(times) == 0.0])


def compared_rows(times, until: float = np.inf) -> np.ndarray:
    """Which reference rows are compared: those more than :data:`EVENT_MARGIN` from every reference event,
    before ``until`` (s)."""
    instants = events(times)
    far = (np.min(np.abs(times[:, None] - instants[None, :]), axis=1) > EVENT_MARGIN if len(instants)
           else np.ones(times.shape, bool))
    return far & (times < until)


def deviations(time, table: dict, ours: dict, until: float = np.inf) -> dict[str, float]:
    """Each comparison signal's worst deviation from the reference ``table``, over its range
    (:func:`signal_range`), at the rows :func:`compared_rows` keeps (``ours``: signal -> our series on the
    run's rows, whose instants are ``time``)."""
    times = table["time"]
    kept = compared_rows(times, until)
    return {signal: float(np.max(np.abs(np.interp(times, time, series) - table[signal])[kept])
                          / signal_range(table[signal])) for signal, series in ours.items()}


def signal_range(values) -> float:
    """A signal's range; one that never moves (a mass at rest throughout), its magnitude, at least 1 of its unit."""
    spread = np.ptp(values)
    return spread if spread > 0.0 else max(float(np.max(np.abs(values))), 1.0)

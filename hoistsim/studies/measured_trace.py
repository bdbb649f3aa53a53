"""A trace measured on a rig: a CSV file whose header names its columns as a results file does, units in brackets.

    time [s],motor_speed [rpm],drum_speed [rpm]
    0.00,300.1,0.02
    0.01,299.8,0.01

Each column is read into the SI unit of the run's series of that name (a column in rpm against a
series in rad/s, in degC against one in K).  Every problem is one line naming the file, the line and
the column: a column the fit matches that is missing, a unit that is unknown or of another kind than
the series', a value that is not a number, times that do not increase.
"""

from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import ScenarioError

_HEADER = re.compile(r"\s*([A-Za-z_][\w.]*)\s*(?:\[([^\]]*)\])?\s*$")


@dataclass
class Trace:
    """Measured columns on their times, in SI (the series' units), and each column's unit as written."""

    source: str
    time: np.ndarray
    columns: dict[str, np.ndarray]
    written: dict[str, str]  # column -> its unit as the file writes it
    units: dict[str, str]  # column -> the series' units, in which ``columns`` are

    def shown(self, name: str, values: np.ndarray) -> np.ndarray:
        """Values of a column in the series' units, back in the unit the file writes it in."""
        return _converted(values, self.units[name], self.written[name])

    def grid(self) -> np.ndarray:
        """The run's output times: the measured times, padded with the last to a power of two (at least 64), so
        that traces of like lengths share one compiled program."""
        padded = max(64, 1 << int(np.ceil(np.log2(self.time.size))))
        return np.concatenate([self.time, np.full(padded - self.time.size, self.time[-1])])


def read_trace(path: str | Path, match: list[str], series_units: dict[str, str], duration: float) -> Trace:
    """The columns ``match`` of a measured CSV trace and its ``time`` column, each in the units of the run's
    series (``series_units``: name -> units); times within ``duration``."""
    source = str(path)
    try:
        with open(path, newline="", encoding="utf-8") as handle:
            rows = list(csv.reader(handle))
    except FileNotFoundError:
        raise ScenarioError("--measured", "no such file", source=source) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError("--measured", f"cannot read it as a CSV text file ({exc})", source=source) from None
    if not rows:
        raise ScenarioError("--measured", "the file is empty; it needs a header like 'time [s],motor_speed [rpm]'",
                            source=source)
    header = {}
    for k, cell in enumerate(rows[0]):
        found = _HEADER.match(cell)
        if not found:
            raise ScenarioError("--measured", f"column {k + 1}: {cell!r} is not a name with its unit in "
                                              "brackets, like 'motor_speed [rpm]'", source=source, line=1)
        header[found.group(1)] = (k, (found.group(2) or "").strip())
    for name in ["time", *match]:
        if name not in header:
            known = ", ".join(n for n in series_units if n != "time")
            raise ScenarioError("--measured", f"has no column {name!r} (its header: {', '.join(header)}); "
                                + ("a trace needs its times, 'time [s]'" if name == "time" else
                                   f"the run's series are {known}"), source=source, line=1)
    units = {"time": "s", **{name: series_units[name] for name in match}}
    data = {name: np.empty(len(rows) - 1) for name in units}
    for line, row in enumerate(rows[1:], start=2):
        for name in units:
            k = header[name][0]
            try:
                value = float(row[k])
            except (IndexError, ValueError):
                cell = row[k] if k < len(row) else ""
                raise ScenarioError("--measured", f"column {name}: {cell!r} is not a number", source=source,
                                    line=line) from None
            if not math.isfinite(value):
                raise ScenarioError("--measured", f"column {name}: {row[k]!r} is not a finite number",
                                    source=source, line=line)
            data[name][line - 2] = value
    if data["time"].size < 2:
        raise ScenarioError("--measured", "needs at least two rows of measurements", source=source)
    written = {}
    for name, si in units.items():
        unit = header[name][1]
        if not unit:
            raise ScenarioError("--measured", f"column {name}: give its unit in brackets, like '{name} [{si}]'",
                                source=source, line=1)
        try:
            data[name] = _converted(data[name], unit, si)
        except ValueError as exc:
            raise ScenarioError("--measured", f"column {name}: {exc}", source=source, line=1) from None
        written[name] = unit
    time = data.pop("time")
    steps = np.diff(time)
    if np.any(steps <= 0):
        line = int(np.flatnonzero(steps <= 0)[0]) + 3
        raise ScenarioError("--measured", "the times must increase from row to row", source=source, line=line)
    if time[0] < 0 or time[-1] > duration * (1 + 1e-12):
        raise ScenarioError("--measured", f"the times run from {time[0]:g} s to {time[-1]:g} s, outside the run's "
                                          f"0 s to {duration:g} s (simulation.duration)", source=source)
    return Trace(source, time, data, {name: written[name] for name in match}, {name: units[name] for name in match})


def _converted(values: np.ndarray, unit: str, to: str) -> np.ndarray:
    """``values`` in ``unit`` as numbers in ``to``; a ValueError saying why where they do not convert."""
    from ..scenario.units import registry

    ureg = registry()
    try:
        return np.asarray(ureg.Quantity(np.asarray(values, dtype=float), unit).to(to).magnitude, dtype=float)
    except Exception as exc:  # pint's: an unknown unit, another dimension
        problem = str(exc).splitlines()[0]
        if "dimension" in type(exc).__name__.lower() or "cannot convert" in problem.lower():
            raise ValueError(f"'{unit}' is not a unit of the series' kind ({to})") from None
        raise ValueError(f"'{unit}' is not a unit hoistsim knows ({problem})") from None

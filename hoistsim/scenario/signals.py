"""Time signals in scenario files: a constant, a table of time, or an offset plus harmonics in time.

A drivetrain's torques and clutch forces are signals of time:
- a constant, ``10 N*m``;
- a table ``[[t, value], ...]``, piecewise linear, a repeated time a step (held beyond its ends);
- ``{offset: value, harmonics: [{amplitude, frequency, phase}, ...]}``: the offset plus each
  amplitude * sin(2 pi frequency t + phase), the harmonics' sum times ``envelope`` where one is given: a
  table of time ``[[t, factor], ...]`` (a sine switched off at 0.5 s: ``[[0 s, 1], [0.5 s, 1], [0.5 s, 0]]``,
  Modelica's Product of a Sine and a Step).
Every form is read into one :class:`TimeSignal`: a table (one row for a constant or an offset) and
harmonics (none for a table) with their envelope (none: 1), so that an element evaluates all of them the
same way.
"""

from __future__ import annotations

import math
from typing import Annotated, Any

import numpy as np
from pydantic import BaseModel, BeforeValidator, ConfigDict

from .tables import TableError, time_rows
from .units import ANGLE, DIMENSIONLESS, FREQUENCY, Dimension, UnitError, check_range, to_si


class TimeSignal(BaseModel):
    """A table of time (SI) plus harmonics: value(t) = table(t) + envelope(t) sum A sin(2 pi f t + phi)."""

    model_config = ConfigDict(frozen=True)
    times: tuple[float, ...]
    values: tuple[float, ...]
    amplitudes: tuple[float, ...] = ()
    frequencies: tuple[float, ...] = ()  # Hz
    phases: tuple[float, ...] = ()  # rad
    # a table of time scaling the harmonics (its knots segment boundaries, a repeated time a step); none: 1
    envelope_times: tuple[float, ...] | None = None  # s
    envelope_values: tuple[float, ...] | None = None  # 1

    @property
    def has_harmonics(self) -> bool:
        return bool(self.amplitudes)

    def value_at(self, t: float) -> float:
        """Its value at time ``t`` (s), as an element reads it: the table, plus the harmonics times their
        envelope."""
        harmonics = sum(a * math.sin(2.0 * math.pi * f * t + p)
                        for a, f, p in zip(self.amplitudes, self.frequencies, self.phases))
        if self.envelope_times is not None:
            harmonics *= float(np.interp(t, self.envelope_times, self.envelope_values))
        return float(np.interp(t, self.times, self.values)) + harmonics


def _harmonics(value: dict, dimension: Dimension) -> TimeSignal:
    unknown = set(value) - {"offset", "harmonics", "envelope"}
    if unknown:
        raise UnitError(f"unknown key {sorted(unknown)[0]!r}: a signal in harmonics has offset, harmonics and "
                        "envelope")
    rows = value.get("harmonics") or []
    if not isinstance(rows, list):
        raise UnitError("harmonics must be a list of {amplitude, frequency, phase}")
    offset = to_si(value.get("offset", 0.0), dimension)
    amplitudes, frequencies, phases = [], [], []
    for i, row in enumerate(rows):
        if not isinstance(row, dict) or "amplitude" not in row or "frequency" not in row:
            raise TableError(i, f"a harmonic is {{amplitude, frequency, phase}}, got {row!r}")
        extra = set(row) - {"amplitude", "frequency", "phase"}
        if extra:
            raise TableError(i, f"unknown key {sorted(extra)[0]!r} (a harmonic has amplitude, frequency, phase)")
        try:
            amplitudes.append(to_si(row["amplitude"], dimension))
            frequencies.append(check_range(to_si(row["frequency"], FREQUENCY), row["frequency"], FREQUENCY, ge=0))
            phases.append(to_si(row.get("phase", 0.0), ANGLE))
        except UnitError as exc:
            raise TableError(i, str(exc)) from None
    envelope = {}
    if value.get("envelope") is not None:
        if not amplitudes:
            raise UnitError("an envelope scales the harmonics: give harmonics with it")
        if not isinstance(value["envelope"], (list, tuple)) or not value["envelope"]:
            raise UnitError("envelope must be a table [[time, factor], ...], like [[0 s, 1], [0.5 s, 1], [0.5 s, 0]]")
        try:
            times, factors = time_rows(value["envelope"], DIMENSIONLESS, "[0.5 s, 1]")
        except TableError as exc:
            raise UnitError(f"envelope {exc}") from None
        envelope = {"envelope_times": times, "envelope_values": factors}
    return TimeSignal(times=(0.0,), values=(offset,), amplitudes=tuple(amplitudes),
                      frequencies=tuple(frequencies), phases=tuple(phases), **envelope)


def time_signal(value: Any, dimension: Dimension) -> TimeSignal:
    """Read a signal of ``dimension`` in any of its three forms (a bad one: a UnitError saying what to give)."""
    if isinstance(value, TimeSignal):
        return value
    if isinstance(value, dict):
        return _harmonics(value, dimension)
    if isinstance(value, (list, tuple)):
        if not value:
            raise UnitError(f"the table is empty; give rows [time, {dimension.name}]")
        times, values = time_rows(value, dimension, f"[0.4 s, {dimension.example.strip(chr(39))}]")
        return TimeSignal(times=times, values=values)
    try:
        return TimeSignal(times=(0.0,), values=(to_si(value, dimension),))
    except UnitError as exc:
        raise UnitError(f"{exc}; or a table [[time, {dimension.name}], ...], or {{offset, harmonics}}") from None


def signal(dimension: Dimension):
    """A pydantic field type: a time signal of ``dimension``."""
    return Annotated[TimeSignal, BeforeValidator(lambda value: time_signal(value, dimension)), dimension]

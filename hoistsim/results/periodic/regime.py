"""The periodic regime read from a run's rows: each period, when the regime settled, the analysed periods.

Everything here comes from rows the run stopped at: the start of every
period (the motor angle a whole multiple of the machine's period), every
maximum and minimum of the motor speed and of the kinetic energy, and every
switch.  Between two rows the speed is monotone and the energy too, so the
extremes over a period are extremes over its rows: exact, not sampled.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ...switch_kinds import SWITCH_KINDS

# Successive periods agree when their mean, maximum and minimum speeds differ by
# less than this many times the run's rtol (relative to the mean speed): well
# above the integration error, which would otherwise never let it settle, and
# small enough that what remains of the transient is far below any irregularity
# worth reporting.
SETTLING_RTOL_FACTOR = 1000.0
# ...and never less than this (an rtol near round-off).
SETTLING_FLOOR = 1e-12



@dataclass
class Regime:
    """The periods of one run and what was found in them."""

    period: float  # rad of motor angle
    table: dict[str, np.ndarray]  # one entry per complete period (see ``period_table``)
    settled_at: int | None  # index in ``table`` of the first analysed period; None: it never settled
    analysed: slice  # the analysed periods' indices in ``table``
    tolerance: float  # relative agreement of successive periods taken as settled
    message: str = ""  # why there is no analysis, if there is none
    units: dict[str, str] = field(default_factory=dict)

    @property
    def settled(self) -> bool:
        return self.settled_at is not None

    def values(self) -> dict[str, float]:
        """The summary of the analysed periods (NaN where the regime did not settle)."""
        t = {name: column[self.analysed] for name, column in self.table.items()}
        if not self.settled:
            nan = math.nan
            return {"period": self.period, "settling_periods": -1, "mean_speed": nan, "max_speed": nan,
                    "min_speed": nan, "max_speed_angle": nan, "min_speed_angle": nan, "irregularity": nan,
                    "energy_fluctuation": nan,
                    **{name: nan for name in self.table if name.endswith("_per_period")}}
        mean = float(np.mean(t["mean_speed"]))
        top, bottom = int(np.argmax(t["max_speed"])), int(np.argmin(t["min_speed"]))
        out = {
            "period": self.period,
            "settling_periods": int(self.settled_at),
            "mean_speed": mean,
            "max_speed": float(t["max_speed"][top]),
            "min_speed": float(t["min_speed"][bottom]),
            "max_speed_angle": float(t["max_speed_angle"][top]),
            "min_speed_angle": float(t["min_speed_angle"][bottom]),
            "irregularity": float((t["max_speed"][top] - t["min_speed"][bottom]) / mean),
            "energy_fluctuation": float(np.max(t["energy_fluctuation"])),
        }
        out.update({name: float(np.mean(column)) for name, column in t.items() if name.endswith("_per_period")})
        return out


PERIOD_UNITS = {
    "period": "1", "start_time": "s", "end_time": "s", "start_angle": "rad", "start_speed": "rad/s",
    "mean_speed": "rad/s", "max_speed": "rad/s", "max_speed_angle": "rad", "min_speed": "rad/s",
    "min_speed_angle": "rad", "irregularity": "1", "energy_fluctuation": "J", "switches_per_period": "1",
    "analysed": "1",
}

PERIOD_DESCRIPTIONS = {
    "period": "period number: 1 starts at the first whole period of motor angle after the start",
    "start_time": "time the period starts",
    "end_time": "time the period ends",
    "start_angle": "motor angle where the period starts",
    "start_speed": "motor speed where the period starts",
    "mean_speed": "mean motor speed over the period's angle, (1/period) integral of w dtheta",
    "max_speed": "largest motor speed in the period",
    "max_speed_angle": "motor angle of the largest speed, from the period's start",
    "min_speed": "smallest motor speed in the period",
    "min_speed_angle": "motor angle of the smallest speed, from the period's start",
    "irregularity": "(max_speed - min_speed) / mean_speed",
    "energy_fluctuation": "largest less smallest kinetic energy of the machine in the period",
    "switches_per_period": "coupling mode switches in the period",
    "analysed": "1 for the periods the summary analyses (the regime settled), else 0",
}


def period_marks(rows: dict) -> np.ndarray:
    """Indices of the rows where a period starts, turning forwards (each ends the one before)."""
    return np.flatnonzero((rows["kind"] == "period") & (rows["motor_speed"] > 0))


def period_table(rows: dict, period: float, loss_columns: list[str],
                 switch_kinds=SWITCH_KINDS) -> dict[str, np.ndarray]:
    """One entry per complete period between two period rows, from a run's rows (Readout.event_rows).

    ``loss_columns``: energy losses (J, growing) whose increase per period is reported as
    ``<name>_per_period`` (the heat a clutch makes each period of a periodic stick-slip).  ``switch_kinds``: the
    machine's switches, the core's and those its parts rename (``Layout.switch_kinds``), counted per period.
    """
    kind = rows["kind"]
    marks = period_marks(rows)
    count = max(0, marks.size - 1)
    out: dict[str, list] = {name: [] for name in PERIOD_UNITS if name != "analysed"}
    out.update({f"{name}_per_period": [] for name in loss_columns})
    speed, angle, energy = rows["motor_speed"], rows["motor_angle"], rows["kinetic_energy"]
    switches = np.isin(kind, switch_kinds)
    for j in range(count):
        a, b = marks[j], marks[j + 1]
        inside = slice(a, b + 1)
        top = a + int(np.argmax(speed[inside]))
        bottom = a + int(np.argmin(speed[inside]))
        mean = (rows["speed_angle_integral"][b] - rows["speed_angle_integral"][a]) / period
        out["period"].append(j + 1)
        out["start_time"].append(rows["time"][a])
        out["end_time"].append(rows["time"][b])
        out["start_angle"].append(angle[a])
        out["start_speed"].append(speed[a])
        out["mean_speed"].append(mean)
        out["max_speed"].append(speed[top])
        out["max_speed_angle"].append(angle[top] - angle[a])
        out["min_speed"].append(speed[bottom])
        out["min_speed_angle"].append(angle[bottom] - angle[a])
        out["irregularity"].append((speed[top] - speed[bottom]) / mean)
        out["energy_fluctuation"].append(np.max(energy[inside]) - np.min(energy[inside]))
        out["switches_per_period"].append(int(np.count_nonzero(switches[a + 1: b + 1])))
        for name in loss_columns:
            out[f"{name}_per_period"].append(rows[name][b] - rows[name][a])
    return {name: np.asarray(values, dtype=int if name in ("period", "switches_per_period") else float)
            for name, values in out.items()}


def settling_tolerance(rtol: float) -> float:
    return max(SETTLING_RTOL_FACTOR * rtol, SETTLING_FLOOR)


def first_settled(table: dict, tolerance: float) -> int | None:
    """Index of the first period of the settled regime, or None.

    A period has settled when it agrees with the one before (mean, maximum and
    minimum speed, relative to the mean) within ``tolerance``, and so does what
    is left of the transient: a transient that dies away by a factor q each
    period still has q / (1 - q) times its last change to go, so a slow one
    (a heavy flywheel on a soft motor) must shrink further before it counts as
    settled.  Changes within the tolerance that do not shrink, or that flip
    sign from one period to the next, are not a transient but the
    integration's drift or noise: settled.  A change below a hundredth of the
    tolerance is settled too.
    """
    stats = np.stack([table["mean_speed"], table["max_speed"], table["min_speed"]], axis=1)
    if stats.shape[0] < 2:
        return None
    steps = np.diff(stats, axis=0) / np.abs(table["mean_speed"][1:, None])
    change = np.max(np.abs(steps), axis=1)
    for k, now in enumerate(change):
        if now <= tolerance / 100:
            return k + 1
        if now > tolerance or k == 0 or change[k - 1] == 0:
            continue
        shrink = now / change[k - 1]
        if shrink >= 1.0 or np.all(steps[k] * steps[k - 1] <= 0):
            return k + 1  # not shrinking, or turned back: the integration's drift or noise, not a transient
        shrink = min(shrink, 0.999)
        if now * shrink / (1 - shrink) <= tolerance:
            return k + 1
    return None


def analyse(rows: dict, period: float, periods: int, rtol: float, duration: float,
            loss_columns: list[str], switch_kinds=SWITCH_KINDS) -> Regime:
    """Settle, then analyse ``periods`` periods: the :class:`Regime` of one run (``switch_kinds``: as
    :func:`period_table`'s)."""
    table = period_table(rows, period, loss_columns, switch_kinds)
    tolerance = settling_tolerance(rtol)
    settled_at = first_settled(table, tolerance)
    count = table["period"].size
    units = dict(PERIOD_UNITS, **{f"{name}_per_period": "J" for name in loss_columns})
    message = ""
    if settled_at is not None and settled_at + periods > count:
        message = (f"the periodic regime settled after {settled_at} periods, but only {count - settled_at} of the "
                   f"{periods} periods to analyse (periodic.periods) followed within the duration "
                   f"({duration:g} s); raise simulation.duration")
        settled_at = None
    elif settled_at is None:
        if count < 2:
            change = "fewer than two whole periods ran"
        else:
            last = [abs(table[k][-1] - table[k][-2]) / abs(table["mean_speed"][-1])
                    for k in ("mean_speed", "max_speed", "min_speed")]
            change = f"the last two of {count} periods still differ by {max(last):.2g} of the mean speed"
        message = (f"the periodic regime has not settled within the duration ({duration:g} s): {change}; "
                   f"settled means successive periods agree within {tolerance:.2g} "
                   f"({SETTLING_RTOL_FACTOR:g} x rtol), and what is left of the transient too; "
                   "raise simulation.duration")
    analysed = slice(settled_at, settled_at + periods) if settled_at is not None else slice(0, 0)
    flags = np.zeros(count, dtype=np.int8)
    flags[analysed] = 1
    table["analysed"] = flags
    return Regime(period=period, table=table, settled_at=settled_at, analysed=analysed, tolerance=tolerance,
                  message=message, units=units)

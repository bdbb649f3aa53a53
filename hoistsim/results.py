"""A finished run: its time series, events, summary and energy balance."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .model import Drivetrain
from .scenario import Scenario


@dataclass
class RunResult:
    """One simulated start-up.

    ``time`` and every array in ``series`` have one entry per output row (the
    output grid plus the event times); ``units`` gives each one's unit.
    """

    scenario: Scenario
    label: str
    drivetrain: Drivetrain
    time: np.ndarray
    series: dict[str, np.ndarray]
    units: dict[str, str]
    events: dict[str, np.ndarray]
    extremes: dict[str, float] = field(default_factory=dict)
    stats: dict = field(default_factory=dict)

    def __getitem__(self, name: str) -> np.ndarray:
        return self.time if name == "time" else self.series[name]

    @property
    def name(self) -> str:
        return self.scenario.name

    # ------------------------------------------------------------------ summary

    @property
    def lockup_time(self) -> float:
        """First time the clutch is locked (s): 0 if it never slips, NaN if it never locks."""
        return self.extremes["lockup_time"]

    @property
    def slip_energy(self) -> float:
        """Energy dissipated in the clutch over the run (J)."""
        return float(self.series["clutch_energy"][-1])

    def _state(self, row: int) -> np.ndarray:
        s = self.series
        return np.array([s["motor_speed"][row], s["drum_speed"][row] * self.drivetrain.ratio,
                         s["load_position"][row], s["clutch_energy"][row], s["motor_work"][row]])

    @property
    def energy_balance(self) -> dict[str, float]:
        """Motor work against kinetic + potential energy + clutch losses (J)."""
        return energy_balance(self.drivetrain, self._state(0), self._state(-1))

    @property
    def summary(self) -> dict:
        """The numbers a designer compares runs by (see :func:`summarize`)."""
        kinds = list(self.events["kind"])
        return summarize(self.label or self.name, self.extremes, self.drivetrain, self._state(0), self._state(-1),
                         kinds.count("lock"), kinds.count("unlock"))

    def to_hdf5(self, path) -> None:
        """Write this run alone to an HDF5 file (atomically)."""
        from .output import write_runs

        write_runs(path, [self])

    def to_xarray(self):
        """The time series as an xarray.Dataset with ``time`` as coordinate (needs xarray)."""
        import xarray as xr

        data = {name: ("time", values, {"units": self.units[name]}) for name, values in self.series.items()}
        return xr.Dataset(data, coords={"time": ("time", self.time, {"units": "s"})},
                          attrs={"name": self.name, "label": self.label})


def energy_balance(drivetrain: Drivetrain, first, last) -> dict[str, float]:
    """Motor work against kinetic + potential energy + clutch losses (J), from two states.

    States are (motor speed, pinion speed, load position, clutch energy, motor
    work).  ``residual`` is what does not balance; ``relative_residual`` divides
    it by the largest of the terms.
    """
    kinetic = drivetrain.kinetic_energy(last[0], last[1]) - drivetrain.kinetic_energy(first[0], first[1])
    potential = drivetrain.load_weight * (last[2] - first[2])
    clutch, work = last[3] - first[3], last[4] - first[4]
    residual = work - (kinetic + potential + clutch)
    scale = max(abs(work), abs(kinetic), abs(potential), abs(clutch), 1e-300)
    return {
        "motor_work": float(work),
        "kinetic_energy_change": float(kinetic),
        "potential_energy_change": float(potential),
        "clutch_energy": float(clutch),
        "residual": float(residual),
        "relative_residual": float(abs(residual) / scale),
    }


def summarize(label: str, extremes: dict, drivetrain: Drivetrain, first, last, locks: int, unlocks: int) -> dict:
    """The numbers a designer compares runs by, from a run's end states and running extremes.

    Peaks and the lowest load position are exact: the run stops at every slip
    peak and load turnaround (and at every switch) to record them.
    """
    balance = energy_balance(drivetrain, first, last)
    return {
        "label": label,
        **{k: float(v) for k, v in extremes.items()},
        "slip_energy": float(last[3]),
        "final_motor_speed": float(last[0]),
        "final_drum_speed": float(last[1] / drivetrain.ratio),
        "final_load_position": float(last[2]),
        "load_lifted": bool(last[2] > 0),
        "lock_events": int(locks),
        "unlock_events": int(unlocks),
        "energy_residual": balance["residual"],
        "energy_relative_residual": balance["relative_residual"],
    }

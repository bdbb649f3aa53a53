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

    @property
    def energy_balance(self) -> dict[str, float]:
        """Motor work against kinetic + potential energy + clutch losses (J).

        ``residual`` is what does not balance; ``relative_residual`` divides it
        by the motor work (or the largest term, if that is larger).
        """
        dt = self.drivetrain
        ws = self.series["motor_speed"]
        wb = self.series["drum_speed"] * dt.ratio
        kinetic = dt.kinetic_energy(ws[-1], wb[-1]) - dt.kinetic_energy(ws[0], wb[0])
        potential = dt.load_weight * self.series["load_position"][-1]
        clutch = self.series["clutch_energy"][-1]
        work = self.series["motor_work"][-1]
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

    @property
    def summary(self) -> dict:
        """The numbers a designer compares runs by.

        Peaks and the lowest load position are exact: the run stops at every slip
        peak and load turnaround (and at every switch) to record them.
        """
        s = self.series
        kinds = list(self.events["kind"])
        balance = self.energy_balance
        return {
            "label": self.label,
            **self.extremes,
            "slip_energy": self.slip_energy,
            "final_motor_speed": float(s["motor_speed"][-1]),
            "final_drum_speed": float(s["drum_speed"][-1]),
            "final_load_position": float(s["load_position"][-1]),
            "load_lifted": bool(s["load_position"][-1] > 0),
            "lock_events": kinds.count("lock"),
            "unlock_events": kinds.count("unlock"),
            "energy_residual": balance["residual"],
            "energy_relative_residual": balance["relative_residual"],
        }

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

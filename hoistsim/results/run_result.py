"""A finished run: its time series, events, summary and energy balance."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..machine.core.ledger import balance
from ..scenario.loading import Scenario
from .run_summaries import summarize
from .summaries import Summaries as Summaries  # noqa: F401  (part of this module's interface)


@dataclass
class RunResult:
    """One simulated start-up.

    ``time`` and every array in ``series`` have one entry per output row (the
    output grid plus the event times); ``units`` and ``descriptions`` give each
    one's unit and meaning.  ``values`` are the elements' summary values
    (lockup_time, slip_energy, ...), ``ledger`` every energy term they declare
    at the start and the end of the run.
    """

    scenario: Scenario
    label: str
    time: np.ndarray
    series: dict[str, np.ndarray]
    units: dict[str, str]
    events: dict[str, np.ndarray]
    values: dict = field(default_factory=dict)  # the elements' summary values (exact extremes, end values)
    ledger: dict = field(default_factory=dict)
    descriptions: dict[str, str] = field(default_factory=dict)
    stats: dict = field(default_factory=dict)
    periodic: object = None  # hoistsim.results.periodic.analysis.Periodic, for a machine with a periodic regime
    grid: np.ndarray | None = None  # the output grid's times (rows of ``time`` that are not event instants)
    # every exact instant, events and observations alike (time, kind, element, torque_margin, mode_after,
    # category: "switch", "scheduled", "observation", "limit" or "cycle"); ``events`` keeps the switches and
    # schedule
    instants: dict | None = None
    summary_units: dict = field(default_factory=dict)  # summary value -> units (results.output.summary_units)

    def grid_rows(self) -> np.ndarray:
        """Indices of the output grid's rows in ``time`` (a grid time that is also an event time: its row)."""
        return np.searchsorted(self.time, self.grid)

    def instant_rows(self) -> np.ndarray:
        """Indices in ``time`` of the rows of ``instants`` (the state just after each)."""
        return np.searchsorted(self.time, self.instants["time"])

    def __getitem__(self, name: str) -> np.ndarray:
        return self.time if name == "time" else self.series[name]

    @property
    def name(self) -> str:
        return self.scenario.name

    # ------------------------------------------------------------------ summary

    @property
    def lockup_time(self) -> float:
        """First time the clutch is locked (s): 0 if it never slips, NaN if it never locks."""
        return self.values["lockup_time"]

    @property
    def slip_energy(self) -> float:
        """Energy dissipated in the clutch over the run (J)."""
        return float(self.series["clutch_energy"][-1])

    @property
    def warnings(self) -> list[str]:
        """What the user should know about this run that is not a failure (a regime that has not settled)."""
        if self.periodic is not None and not self.periodic.regime.settled:
            return [f"{self.label or self.name}: {self.periodic.regime.message}"]
        return []

    @property
    def energy_balance(self) -> dict[str, float]:
        """Work done on the machine against kinetic + potential energy + every loss (J)."""
        return balance(self.ledger)

    @property
    def summary(self) -> dict:
        """The numbers a designer compares runs by (see :func:`summarize`)."""
        kinds = list(self.events["kind"])
        return summarize(self.label or self.name, self.values, self.ledger, kinds.count("lock"),
                         kinds.count("unlock"))

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

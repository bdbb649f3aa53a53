"""A run's periodic regime and Tredgold's answer beside it: the summary values and the period table."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...machine.core.readout import Readout
from .regime import Regime, analyse, period_marks
from .tredgold import Diagram, diagram

SUMMARY_UNITS = {
    "period": "rad", "settling_periods": "1", "mean_speed": "rad/s", "max_speed": "rad/s", "min_speed": "rad/s",
    "max_speed_angle": "rad", "min_speed_angle": "rad", "irregularity": "1", "irregularity_tredgold": "1",
    "energy_fluctuation": "J", "energy_fluctuation_tredgold": "J", "inertia_tredgold": "kg*m^2",
    "switches_per_period": "1",
}


@dataclass
class Periodic:
    """The periodic regime of a run: its periods, and the turning-moment diagram of its analysed regime."""

    regime: Regime
    diagram: Diagram | None  # None where the regime did not settle

    def values(self) -> dict:
        out = self.regime.values()
        d = self.diagram
        out["irregularity_tredgold"] = d.irregularity if d is not None else math.nan
        out["energy_fluctuation_tredgold"] = d.energy_fluctuation if d is not None else math.nan
        out["inertia_tredgold"] = d.inertia if d is not None else math.nan
        return out



def periodic_element(layout):
    return next((e for e in layout.elements if e.cycles), None)


def periodic_summary_units(layout) -> dict[str, str]:
    """Units of the periodic summary values of a machine (none for one without a periodic regime)."""
    if periodic_element(layout) is None:
        return {}
    return dict(SUMMARY_UNITS, **{f"{name}_per_period": "J" for name in loss_columns(layout)})


def loss_columns(layout) -> list[str]:
    """Energy losses that are also output columns: their growth per period is reported."""
    return [name for name, kind in layout.ledger_kinds.items() if kind == "loss" and name in layout.columns()]


def periodic_regime(scenario, readout: Readout) -> Periodic | None:
    """The periodic regime of a finished run, or None for a machine that has none."""
    layout = readout.layout
    element = periodic_element(layout)
    if element is None:
        return None
    rows = readout.event_rows()
    sim = scenario.simulation
    period = float(element.cycle_angle())
    regime = analyse(rows, period, scenario.periodic_regime.periods, sim.rtol, sim.duration, loss_columns(layout),
                     layout.switch_kinds)
    if not regime.settled:
        return Periodic(regime, None)
    # the diagram from where the first analysed period starts (the drum's angle there included)
    start = period_marks(rows)[regime.settled_at]
    state = np.stack([rows[name][start] for name in layout.state_names])
    mean = float(np.mean(regime.table["mean_speed"][regime.analysed]))
    return Periodic(regime, diagram(layout.elements, state, float(rows["time"][start]), mean, period))

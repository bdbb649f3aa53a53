"""What the load's two variants share: its height as a state, its potential energy, what a designer reads."""

from __future__ import annotations

import abc
from typing import ClassVar

from ..core.element import AbstractElement
from ..core.panel import Panel, SummaryPanel, Trace


class AbstractLoad(AbstractElement):
    """A mass M lifted by the rope: its height above its start is a state (rate: its speed, ``load_speed``)
    and its potential energy M g x is in the ledger.  Its lowest point, where a load that ran back turns
    round, is an observation, so the summary's lowest position is exact.  Both variants declare the
    shaft ``rope_point``: the rope's point on the drum (m/s, R times the drum's speed)."""

    mass: object  # M, kg
    gravity: object  # g, m/s^2
    rope_radius: object  # R, m

    section: ClassVar[str] = "load"
    summaries: ClassVar[dict] = {"lowest_load_position": "m", "final_load_position": "m", "load_lifted": "bool"}
    ledger_kinds: ClassVar[dict] = {"potential_energy": "potential"}
    observation_kinds: ClassVar[tuple] = ("load_lowest",)
    columns: ClassVar[dict] = {
        "load_position": ("m", "height of the load above its start"),
        "load_velocity": ("m/s", "rope speed, positive up"),
    }
    panels: ClassVar[tuple] = (
        Panel("load_position", "load height [m]\n(above its start)", 30,
              (Trace("load", "load_position", marks=("load_lowest",)),), zero_line=True, height=0.8),
        Panel("load_velocity", "load speed [m/s]\n(+ up)", 31, (Trace("load", "load_velocity"),),
              zero_line=True, height=0.8),
    )
    summary_panels: ClassVar[tuple] = (
        SummaryPanel("lowest_load_position", "lowest load position [m]", 30, zero_line=True),
        SummaryPanel("final_load_position", "load position at the end [m]", 31, zero_line=True),
    )

    @classmethod
    def headline(cls, summary: dict) -> str | None:
        final, lowest = float(summary["final_load_position"]), float(summary["lowest_load_position"])
        if lowest < 0 and final < 0:
            return f"load runs back {-final:.3g} m"
        if lowest < 0:
            return f"load dips {-lowest:.3g} m, ends {final:+.3g} m"
        return f"load {final:+.3g} m"

    @abc.abstractmethod
    def load_speed(self, x):
        """The load's speed (m/s, positive up)."""

    def states(self) -> dict:
        return {"load_position": 0.0}

    def rates(self, x) -> dict:
        return {"load_position": self.load_speed(x)}

    def ledger(self, x) -> dict:
        return {"potential_energy": self.mass * self.gravity * x.state("load_position")}

    def observations(self, x) -> dict:
        # Minus the load's speed falls through zero where a load that ran back turns
        # round; written as a fall from strictly positive, so a load starting
        # from rest (or released by a brake) is not taken for a turnaround.
        return {"load_lowest": -self.load_speed(x)}

    def extremes(self, x) -> dict:
        return {"lowest_load_position": ("min", x.state("load_position"))}

    def outputs(self, x) -> dict:
        return {"load_position": x.state("load_position"), "load_velocity": self.load_speed(x)}

    def summary(self, x) -> dict:
        position = x.state("load_position")
        return {"final_load_position": position, "load_lifted": position > 0}

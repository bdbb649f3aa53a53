"""The hanging load on a rigid rope wound on the drum."""

from __future__ import annotations

from typing import ClassVar

from ..core.element import AbstractElement
from ..core.panel import Panel, SummaryPanel, Trace


class RigidLoad(AbstractElement):
    """A mass M on a rope of radius R on the drum shaft: reduced by equal kinetic energy and power.

    Inertia M R^2 and torque -M g R on the drum shaft; its height is a state
    (rate R omega_drum) and its potential energy M g x is in the ledger.  Its
    lowest point, where a load that ran back turns round, is an observation, so
    the summary's lowest position is exact.
    """

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

    @classmethod
    def from_spec(cls, spec, scenario) -> "RigidLoad":
        return cls(mass=spec.mass, gravity=scenario.gravity, rope_radius=0.5 * scenario.drum.diameter)

    def inertias(self) -> tuple:
        return (("drum", self.mass * self.rope_radius**2),)

    def torques(self, x) -> tuple:
        return (("drum", -self.mass * self.gravity * self.rope_radius),)

    def states(self) -> dict:
        return {"load_position": 0.0}

    def rates(self, x) -> dict:
        return {"load_position": self.rope_radius * x.speed("drum")}

    def ledger(self, x) -> dict:
        return {"potential_energy": self.mass * self.gravity * x.state("load_position")}

    def observations(self, x) -> dict:
        # Minus the drum speed falls through zero where a load that ran back turns
        # round; written as a fall from strictly positive, so a drum starting
        # from rest (or released by a brake) is not taken for a turnaround.
        return {"load_lowest": -x.speed("drum")}

    def extremes(self, x) -> dict:
        return {"lowest_load_position": ("min", x.state("load_position"))}

    def outputs(self, x) -> dict:
        return {"load_position": x.state("load_position"), "load_velocity": self.rope_radius * x.speed("drum")}

    def summary(self, x) -> dict:
        position = x.state("load_position")
        return {"final_load_position": position, "load_lifted": position > 0}

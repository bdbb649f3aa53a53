"""What the load's two variants share: its height as a state, its potential energy, what a designer reads."""

from __future__ import annotations

import abc
from typing import ClassVar

from ..._pytree import static
from ..core.element import AbstractElement


class AbstractLoad(AbstractElement):
    """A mass M lifted by the rope: its height above its start is a state (rate: its speed, ``load_speed``)
    and its potential energy M g x is in the ledger.  Its lowest point, where a load that ran back turns
    round, is an observation, so the summary's lowest position is exact.  Both variants declare the
    shaft ``rope_point``: the rope's point on the drum (m/s, R times the drum's speed).  Built from a drawn
    load (``drivetrain.load``; the hoist's ``load`` with its ``rope``, ``ground`` and ``bearings``)."""

    mass: object  # M, kg
    gravity: object  # g, m/s^2
    rope_radius: object  # R, m
    drum: str = static("drum")  # the shaft its rope is wound on

    section: ClassVar[str] = "load"
    summaries: ClassVar[dict] = {"lowest_load_position": "m", "final_load_position": "m", "load_lifted": "bool"}
    ledger_kinds: ClassVar[dict] = {"potential_energy": "potential"}
    observation_kinds: ClassVar[tuple] = ("load_lowest",)
    columns: ClassVar[dict] = {
        "load_position": ("m", "height of the load above its start"),
        "load_velocity": ("m/s", "rope speed, positive up"),
    }

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

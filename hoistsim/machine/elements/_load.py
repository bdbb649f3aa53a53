"""What the load's variants share: a mass on a line named ``load``; a hanging one's weight, its potential energy,
what a designer reads of it."""

from __future__ import annotations

from typing import ClassVar

from ..._pytree import static
from .mass import Mass


class AbstractLoad(Mass):
    """The load: the mass on a line named ``load`` (:class:`.mass.Mass`), moved by a drum shaft through its rope's
    radius, its position (``load_position``) measured from its start.  The variants declare the shaft
    ``rope_point``: the rope's point on the drum (m/s, R times the drum's speed); on a rigid rope (or a level path)
    the load is geared to it, on an elastic rope it is a body of its own.  Built from a drawn load
    (``drivetrain.load``; the hoist's ``load`` with its ``rope``, ``ground`` and ``bearings``)."""

    gravity: object = 0.0  # g, m/s^2
    rope_radius: object = 0.0  # R, m
    drum: str = static("drum")  # the shaft its rope is wound on

    summaries: ClassVar[dict] = {"final_load_position": "m"}
    shafts_are_parts: ClassVar[bool] = True  # the rope's point is the drum's, a load geared to it the drum's load
    position_words: ClassVar[str] = "height of the load above its start"
    velocity_words: ClassVar[str] = "rope speed, positive up"

    @property
    def columns(self) -> dict:
        return {"load_velocity": ("m/s", self.velocity_words)}

    def angle_columns(self) -> dict:
        return {"load": ("load_position", "m", self.position_words)}

    def shafts(self) -> dict:
        # the rope's point on the drum; the load geared to it where it moves with it (a rigid rope, a level path)
        point = {"rope_point": (self.drum, self.rope_radius)}
        return {**point, "load": ("rope_point", 1.0)} if self.geared_to else point

    def speed_scale(self):
        # the machine's shafts set the slip resolution (rad/s): a load's speed in m/s has no say in it
        return None

    def outputs(self, x) -> dict:
        return {"load_velocity": x.speed("load")}

    def summary(self, x) -> dict:
        return {"final_load_position": x.angle("load")}


class HangingLoad(AbstractLoad):
    """A load lifted by the rope against its weight M g, its potential energy M g x in the ledger.  Its lowest
    point, where a load that ran back turns round, is an observation, so the summary's lowest position is exact."""

    summaries: ClassVar[dict] = {"lowest_load_position": "m", "final_load_position": "m", "load_lifted": "bool"}
    ledger_kinds: ClassVar[dict] = {"potential_energy": "potential"}
    observation_kinds: ClassVar[tuple] = ("load_lowest",)

    def torques(self, x) -> tuple:
        return (("load", -self.mass * self.gravity),)

    def ledger(self, x) -> dict:
        return {"potential_energy": self.mass * self.gravity * x.angle("load")}

    def observations(self, x) -> dict:
        # Minus the load's speed falls through zero where a load that ran back turns
        # round; written as a fall from strictly positive, so a load starting
        # from rest (or released by a brake) is not taken for a turnaround.
        return {"load_lowest": -x.speed("load")}

    def extremes(self, x) -> dict:
        return {"lowest_load_position": ("min", x.angle("load"))}

    def summary(self, x) -> dict:
        position = x.angle("load")
        return {"final_load_position": position, "load_lifted": position > 0}

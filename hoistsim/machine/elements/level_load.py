"""A load a drawn drivetrain's shaft moves along a level path through a radius (Modelica's IdealRollingWheel
and a Translational Mass)."""

from __future__ import annotations

from typing import ClassVar

from ..._pytree import static
from ..core.element import AbstractElement


class LevelLoad(AbstractElement):
    """A mass M moved through a radius R by its shaft (a wheel rolling it, a rope towing it) along a level path,
    so no gravity acts along it: inertia M R^2 on the shaft, nothing else (a drag is a part of its own, the
    load's ``drag``).  Its distance from its start is a state.  Like a hoisted load it declares the shafts
    ``rope_point`` (R times its shaft's speed) and ``load`` (its speed, m/s), where its drag acts."""

    mass: object  # M, kg
    rope_radius: object  # R, m
    drum: str = static("")  # the shaft that moves it

    section: ClassVar[str] = "load"
    summaries: ClassVar[dict] = {"final_load_position": "m"}
    columns: ClassVar[dict] = {
        "load_position": ("m", "distance the load has moved along its level path from its start"),
        "load_velocity": ("m/s", "speed of the load along its level path, positive as its shaft turns forwards"),
    }

    @classmethod
    def from_spec(cls, spec) -> "LevelLoad":
        return cls(mass=spec.mass, rope_radius=spec.rope_radius, drum=spec.shaft)

    def shafts(self) -> dict:
        return {"rope_point": (self.drum, self.rope_radius), "load": ("rope_point", 1.0)}

    def inertias(self) -> tuple:
        return ((self.drum, self.mass * self.rope_radius**2),)

    def states(self) -> dict:
        return {"load_position": 0.0}

    def rates(self, x) -> dict:
        return {"load_position": x.speed("load")}

    def summary(self, x) -> dict:
        return {"final_load_position": x.state("load_position")}

    def outputs(self, x) -> dict:
        return {"load_position": x.state("load_position"), "load_velocity": x.speed("load")}

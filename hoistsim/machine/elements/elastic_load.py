"""The load as a body of its own, hanging from an elastic rope."""

from __future__ import annotations

from typing import ClassVar

from ._load import AbstractLoad


class ElasticLoad(AbstractLoad):
    """A mass M with a height and a speed of its own (the body ``load``, in m and m/s), pulled up by the
    rope (its ``rope``) and down by its weight M g.

    It starts at rest on the ground (its ``ground``) or moving with the rope's
    point on the drum (a load hanging on a rope that already carries it).
    """

    initial_speed: object = 0.0  # m/s

    columns: ClassVar[dict] = {
        "load_position": ("m", "height of the load above its start"),
        "load_velocity": ("m/s", "speed of the load itself, positive up (the rope's elasticity between it and the drum)"),
    }

    @classmethod
    def from_spec(cls, spec) -> "ElasticLoad":
        radius = spec.rope_radius
        resting = spec.ground is not None
        return cls(mass=spec.mass, gravity=spec.resolved("gravity"), rope_radius=radius, drum=spec.shaft,
                   initial_speed=0.0 if resting else radius * spec.resolved("start_speed"))

    def bodies(self) -> dict:
        return {"load": self.initial_speed}

    def shafts(self) -> dict:
        return {"rope_point": (self.drum, self.rope_radius)}

    def inertias(self) -> tuple:
        return (("load", self.mass),)

    def torques(self, x) -> tuple:
        return (("load", -self.mass * self.gravity),)

    def load_speed(self, x):
        return x.speed("load")

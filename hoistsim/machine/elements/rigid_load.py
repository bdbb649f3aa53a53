"""The hanging load on a rigid rope wound on the drum."""

from __future__ import annotations

from ._load import AbstractLoad


class RigidLoad(AbstractLoad):
    """A mass M on a rigid rope of radius R on the drum shaft: reduced by equal kinetic energy and power.

    Inertia M R^2 and torque -M g R on the drum shaft; the load moves with the
    rope's point on the drum (the shaft ``load``, R times the drum's speed, is
    what a ground under it holds).
    """

    @classmethod
    def from_spec(cls, spec) -> "RigidLoad":
        return cls(mass=spec.mass, gravity=spec.resolved("gravity"), rope_radius=spec.rope_radius, drum=spec.shaft)

    def shafts(self) -> dict:
        return {"rope_point": (self.drum, self.rope_radius), "load": ("rope_point", 1.0)}

    def inertias(self) -> tuple:
        return ((self.drum, self.mass * self.rope_radius**2),)

    def torques(self, x) -> tuple:
        return ((self.drum, -self.mass * self.gravity * self.rope_radius),)

    def load_speed(self, x):
        return self.rope_radius * x.speed(self.drum)

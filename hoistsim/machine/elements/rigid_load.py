"""The hanging load on a rigid rope wound on the drum."""

from __future__ import annotations

from ._load import HangingLoad


class RigidLoad(HangingLoad):
    """A mass M on a rigid rope of radius R on the drum shaft: the mass ``load`` geared to the rope's point on the
    drum (the shaft ``rope_point``, R times the drum's speed), so it reaches the drum shaft as an inertia M R^2
    and its weight as a torque -M g R (what a ground under it holds)."""

    @classmethod
    def from_spec(cls, spec) -> "RigidLoad":
        return cls(mass=spec.mass, initial_velocity=0.0, section="load", geared_to="rope_point",
                   gravity=spec.resolved("gravity"), rope_radius=spec.rope_radius, drum=spec.shaft)

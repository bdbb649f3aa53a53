"""A load a drawn drivetrain's shaft moves along a level path through a radius (Modelica's IdealRollingWheel
and a Translational Mass)."""

from __future__ import annotations

from typing import ClassVar

from ._load import AbstractLoad


class LevelLoad(AbstractLoad):
    """A mass M moved through a radius R by its shaft (a wheel rolling it, a rope towing it) along a level path,
    so no gravity acts along it: the mass ``load`` geared to the shaft's ``rope_point`` (R times its speed), inertia
    M R^2 on the shaft, nothing else (a drag is a part of its own, the load's ``drag``)."""

    position_words: ClassVar[str] = "distance the load has moved along its level path from its start"
    velocity_words: ClassVar[str] = "speed of the load along its level path, positive as its shaft turns forwards"

    @classmethod
    def from_spec(cls, spec) -> "LevelLoad":
        return cls(mass=spec.mass, initial_velocity=0.0, section="load", geared_to="rope_point",
                   rope_radius=spec.rope_radius, drum=spec.shaft)

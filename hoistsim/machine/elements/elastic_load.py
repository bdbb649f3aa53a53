"""The load as a body of its own, hanging from an elastic rope."""

from __future__ import annotations

from typing import ClassVar

from ._load import HangingLoad


class ElasticLoad(HangingLoad):
    """The mass ``load`` as a body of its own (its height and speed its own, in m and m/s), pulled up by the
    rope (its ``rope``) and down by its weight M g.

    It starts at rest on the ground (its ``ground``) or moving with the rope's
    point on the drum (a load hanging on a rope that already carries it).
    """

    velocity_words: ClassVar[str] = ("speed of the load itself, positive up (the rope's elasticity between it and "
                                     "the drum)")

    @classmethod
    def from_spec(cls, spec) -> "ElasticLoad":
        radius = spec.rope_radius
        resting = spec.ground is not None
        return cls(mass=spec.mass, initial_velocity=0.0 if resting else radius * spec.resolved("start_speed"),
                   section="load", gravity=spec.resolved("gravity"), rope_radius=radius, drum=spec.shaft)

"""A shaft: a body with its inertia and initial speed, or a shaft geared to one (a drawn drivetrain's, the hoist's
motor shaft)."""

from __future__ import annotations

import numpy as np

from ..._pytree import static
from ..core.element import AbstractElement

SPEED_SCALE_FLOOR = 1.0  # rad/s


class Shaft(AbstractElement):
    """A rigid shaft with its inertia, turning at a speed of its own (a body) or geared to another shaft
    (``geared_to``: its speed ``speed_ratio`` times that one's, the same body); its speed is the output
    ``<name>_speed``."""

    inertia: object  # kg*m^2
    initial_speed: object  # rad/s
    speed_ratio: object = 1.0  # its speed over that of the shaft it is geared to
    initial_angle: object = 0.0  # rad
    section: str = static("")  # the shaft's name
    geared_to: str = static("")  # the first shaft of its gear train ("" : it is that shaft)
    angled: bool = static(False)  # its angle is given: a state and an output (<name>_angle) whatever reads it

    @classmethod
    def from_spec(cls, spec) -> Shaft:
        root, ratio, speed = spec.resolved("train")
        return cls(inertia=spec.inertia, initial_speed=speed, speed_ratio=ratio, initial_angle=spec.angle,
                   section=spec.name, geared_to="" if root == spec.name else root,
                   angled="angle" in spec.model_fields_set)

    @property
    def columns(self) -> dict:
        return {f"{self.section}_speed": ("rad/s", f"speed of shaft {self.section}")}

    @property
    def summaries(self) -> dict:
        return {f"final_{self.section}_speed": "rad/s"}

    def bodies(self) -> dict:
        return {} if self.geared_to else {self.section: self.initial_speed}

    def shafts(self) -> dict:
        return {self.section: (self.geared_to, self.speed_ratio)} if self.geared_to else {}

    def inertias(self) -> tuple:
        return ((self.section, self.inertia),)

    def angle_starts(self) -> dict:
        return {self.section: self.initial_angle}

    def angles(self) -> tuple:
        return (self.section,) if self.angled else ()

    def speed_scale(self):
        # at least 1 rad/s: a machine started at rest (or at a speed lost in round-off) still resolves slips
        # against the speeds its torques give it, not against nothing
        return np.maximum(np.abs(self.initial_speed), SPEED_SCALE_FLOOR)

    def outputs(self, x) -> dict:
        return {f"{self.section}_speed": x.speed(self.section)}

    def summary(self, x) -> dict:
        return {f"final_{self.section}_speed": x.speed(self.section)}

"""A shaft of a drawn drivetrain: a body with its inertia and initial speed."""

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
    section: str = static("")  # the shaft's name in drivetrain.shafts
    geared_to: str = static("")  # the first shaft of its gear train ("" : it is that shaft)

    @property
    def columns(self) -> dict:
        return {f"{self.section}_speed": ("rad/s", f"speed of shaft {self.section}")}

    def bodies(self) -> dict:
        return {} if self.geared_to else {self.section: self.initial_speed}

    def shafts(self) -> dict:
        return {self.section: (self.geared_to, self.speed_ratio)} if self.geared_to else {}

    def inertias(self) -> tuple:
        return ((self.section, self.inertia),)

    def speed_scale(self):
        # at least 1 rad/s: a machine started at rest (or at a speed lost in round-off) still resolves slips
        # against the speeds its torques give it, not against nothing
        return np.maximum(np.abs(self.initial_speed), SPEED_SCALE_FLOOR)

    def outputs(self, x) -> dict:
        return {f"{self.section}_speed": x.speed(self.section)}

    # A drawn part: Drivetrain.from_spec builds it with its constructor (its name and its gear train are the
    # drivetrain's to say), not the registry from a section of its own; it takes (spec, scenario) once the
    # registry builds drawn parts too.
    @classmethod
    def from_spec(cls, spec, scenario) -> Shaft:
        raise TypeError("a shaft is built by its drivetrain (Drivetrain.from_spec), not from a section of its own")

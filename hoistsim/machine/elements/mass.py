"""A mass on a line: a body sliding, with its mass, position and velocity (Modelica's Translational Mass)."""

from __future__ import annotations

import numpy as np

from ..._pytree import static
from ..core.element import AbstractElement

VELOCITY_SCALE_FLOOR = 1.0  # m/s


class Mass(AbstractElement):
    """A body as a shaft is, on a line: kg for kg*m^2, N for N*m, m and m/s for rad and rad/s.  Its position is a
    state whatever reads it, its outputs ``<name>_position`` (m) and ``<name>_velocity`` (m/s), so that Modelica's
    s_rel and v_rel of a part between two masses are the second's less the first's.  Geared to a shaft (a rack on
    its pinion, a wheel rolling on the line) or to another mass, it moves with that body (``geared_to``: its
    velocity ``speed_ratio`` times that one's speed), its mass m reaching a shaft as m r^2."""

    mass: object  # kg
    initial_velocity: object  # m/s
    initial_position: object = 0.0  # m
    speed_ratio: object = 1.0  # its velocity over the speed of the body it is geared to (m/rad from a shaft)
    section: str = static("")  # the mass's name
    geared_to: str = static("")  # the first shaft (or mass) of its gear train ("": it is that body)

    @classmethod
    def from_spec(cls, spec) -> "Mass":
        root, ratio, velocity = spec.resolved("train")
        return cls(mass=spec.mass, initial_velocity=velocity, initial_position=spec.position, speed_ratio=ratio,
                   section=spec.name, geared_to="" if root == spec.name else root)

    @property
    def columns(self) -> dict:
        return {f"{self.section}_velocity": ("m/s", f"velocity of mass {self.section}")}

    @property
    def summaries(self) -> dict:
        return {f"final_{self.section}_velocity": "m/s"}

    def bodies(self) -> dict:
        return {} if self.geared_to else {self.section: self.initial_velocity}

    def shafts(self) -> dict:
        return {self.section: (self.geared_to, self.speed_ratio)} if self.geared_to else {}

    def inertias(self) -> tuple:
        return ((self.section, self.mass),)

    def angles(self) -> tuple:
        return (self.section,)

    def angle_starts(self) -> dict:
        return {self.section: self.initial_position}

    def angle_columns(self) -> dict:
        return {self.section: (f"{self.section}_position", "m", f"position of mass {self.section} (its centre)")}

    def speed_scale(self):
        # at least 1 m/s: a mass started at rest still resolves slips against the speeds its forces give it
        return np.maximum(np.abs(self.initial_velocity), VELOCITY_SCALE_FLOOR)

    def outputs(self, x) -> dict:
        return {f"{self.section}_velocity": x.speed(self.section)}

    def summary(self, x) -> dict:
        return {f"final_{self.section}_velocity": x.speed(self.section)}

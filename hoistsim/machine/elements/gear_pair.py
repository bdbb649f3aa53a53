"""The spur gear pair: pinion 1 on the clutch output shaft, wheel 2 on the drum shaft."""

from __future__ import annotations

from typing import ClassVar

from ..core.element import AbstractElement


class GearPair(AbstractElement):
    """Brings the pinion shaft (a body) and the drum shaft geared to it, with their gears' inertias.

    The drum turns z1/z2 times as fast as the pinion; an ideal mesh passes
    power unchanged, so inertia and torque on the drum shaft reach the pinion
    by (z1/z2)^2 and z1/z2.
    """

    pinion_teeth: object  # z1
    wheel_teeth: object  # z2
    pinion_inertia: object  # kg*m^2
    wheel_inertia: object  # kg*m^2
    initial_pinion_speed: object  # rad/s

    section: ClassVar[str] = "gears"

    @classmethod
    def from_spec(cls, spec, scenario) -> "GearPair":
        initial = scenario.initial
        return cls(pinion_teeth=float(spec.pinion_teeth), wheel_teeth=float(spec.wheel_teeth),
                   pinion_inertia=spec.pinion_inertia, wheel_inertia=spec.wheel_inertia,
                   initial_pinion_speed=initial.drum_speed * spec.wheel_teeth / spec.pinion_teeth)

    def bodies(self) -> dict:
        return {"pinion": self.initial_pinion_speed}

    def shafts(self) -> dict:
        return {"drum": ("pinion", self.pinion_teeth / self.wheel_teeth)}

    def inertias(self) -> tuple:
        return (("pinion", self.pinion_inertia), ("drum", self.wheel_inertia))

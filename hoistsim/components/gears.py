"""The spur gear pair: pinion 1 on the clutch output shaft, wheel 2 on the drum shaft."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class GearPair:
    pinion_teeth: int  # z1
    wheel_teeth: int  # z2
    module: float  # m, metres
    pressure_angle: float  # alpha, rad
    pinion_inertia: float = 0.0  # kg*m^2
    wheel_inertia: float = 0.0  # kg*m^2

    @property
    def ratio(self) -> float:
        """tau = z2/z1: pinion turns per drum turn."""
        return self.wheel_teeth / self.pinion_teeth

    @property
    def pinion_pitch_radius(self) -> float:
        return 0.5 * self.module * self.pinion_teeth

    @property
    def wheel_pitch_radius(self) -> float:
        return 0.5 * self.module * self.wheel_teeth

    def tangential_force(self, pinion_torque):
        """Tooth force along the pitch-circle tangent (N) for a pinion torque (N*m)."""
        return pinion_torque / self.pinion_pitch_radius

    def radial_force(self, tangential_force):
        """Separating tooth force (N) of involute teeth: T tan(alpha)."""
        return tangential_force * math.tan(self.pressure_angle)

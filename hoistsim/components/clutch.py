"""The cone clutch: torque capacity from geometry, friction and axial force."""

from __future__ import annotations

import math
from dataclasses import dataclass


@dataclass(frozen=True)
class ConeClutch:
    inner_radius: float  # r_i, m
    outer_radius: float  # r_e, m
    half_angle: float  # beta, rad: friction surface to axis
    static_friction: float  # f_a
    kinetic_friction: float  # f
    surfaces: int = 1  # n
    mean_radius_rule: str = "uniform_wear"

    @property
    def mean_radius(self) -> float:
        """Radius at which the friction force acts (m).

        Uniform wear (a run-in clutch, the exercise's assumption) gives the
        arithmetic mean; uniform pressure (a new clutch) the centroid of the
        annulus, 2/3 (re^3 - ri^3)/(re^2 - ri^2), slightly larger.
        """
        ri, re = self.inner_radius, self.outer_radius
        if self.mean_radius_rule == "uniform_pressure":
            return 2.0 / 3.0 * (re**3 - ri**3) / (re**2 - ri**2)
        return 0.5 * (ri + re)

    @property
    def torque_per_newton(self) -> float:
        """c = n r_m / sin(beta) (m): friction torque per unit axial force and unit friction.

        The wedge of the cone multiplies the normal force by 1/sin(beta).
        """
        return self.surfaces * self.mean_radius / math.sin(self.half_angle)

    def static_capacity(self, engagement_force):
        """Largest torque (N*m) the clutch carries without slipping."""
        return self.static_friction * self.torque_per_newton * engagement_force

    def kinetic_torque(self, engagement_force):
        """Torque (N*m) a slipping clutch transmits."""
        return self.kinetic_friction * self.torque_per_newton * engagement_force

    def force_for_torque(self, torque: float) -> float:
        """Axial force (N) at which the static capacity equals ``torque``."""
        return torque / (self.static_friction * self.torque_per_newton)

"""The drive motor: a linear torque-speed characteristic."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class LinearMotor:
    """C(omega) = C0 (1 - omega/omega0).

    The line is used on both sides of its end points: below zero speed (the load
    dragging the motor backwards) the torque exceeds C0, and above omega0 the motor
    brakes.  That is the usual idealisation of an induction motor's working branch.
    """

    stall_torque: float  # C0, N*m
    no_load_speed: float  # omega0, rad/s
    inertia: float  # J_m, kg*m^2

    def torque(self, speed):
        """Motor torque (N*m) at shaft speed ``speed`` (rad/s); works on arrays."""
        return self.stall_torque * (1.0 - speed / self.no_load_speed)

"""The linear motor: C(omega) = C0 (1 - omega/omega0)."""

from __future__ import annotations

from ._motor import AbstractMotor


class LinearMotor(AbstractMotor):
    """Torque falling linearly from C0 at standstill to zero at omega0.

    The line is used on both sides of its end points: below zero speed (the load
    dragging the motor backwards) the torque exceeds C0, and above omega0 the
    motor brakes.  That is the usual idealisation of an induction motor's
    working branch.
    """

    stall_torque: object  # C0, N*m
    no_load_speed: object  # omega0, rad/s

    @classmethod
    def characteristic_from(cls, spec) -> dict:
        return {"stall_torque": spec.stall_torque, "no_load_speed": spec.no_load_speed}

    def characteristic(self, speed):
        return self.stall_torque * (1.0 - speed / self.no_load_speed)

    def speed_scale(self):
        return self.no_load_speed

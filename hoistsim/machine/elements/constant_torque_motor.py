"""A motor that gives a constant torque whatever its speed (a governed engine; 0: the motor is off)."""

from __future__ import annotations

import jax.numpy as jnp

from ._motor import AbstractMotor


class ConstantTorqueMotor(AbstractMotor):
    """C(omega) = C.  With C = 0 the motor shaft coasts on its own inertia."""

    torque: object  # N*m

    @classmethod
    def characteristic_from(cls, spec) -> dict:
        return {"torque": spec.torque}

    def characteristic(self, speed):
        return self.torque + jnp.zeros_like(speed)

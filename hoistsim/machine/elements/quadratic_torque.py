"""A torque on a shaft of a drawn drivetrain quadratic in the shaft's speed (Modelica's
QuadraticSpeedDependentTorque)."""

from __future__ import annotations

import jax.numpy as jnp

from ..._pytree import static
from ._shaft_work import AbstractShaftWork


class QuadraticTorque(AbstractShaftWork):
    """tau = tau_n (w / w_n)^2, positive in the shaft's positive sense: times sign(w) where its direction
    reverses with the turning (a fan's drag, tau_n < 0), the same both ways where it is fixed.  Smooth (w |w| has
    a continuous slope at rest), so no kink.  Its work on the shaft is a state and a work term of the ledger."""

    nominal_torque: object  # tau_n, N*m
    nominal_speed: object  # w_n, rad/s
    shaft: str = static("")
    section: str = static("")  # torque1, torque2, ... in the order of drivetrain.torques
    reverses: bool = static(True)  # its sign follows the speed's (Modelica's TorqueDirection = false)

    @classmethod
    def from_spec(cls, spec) -> "QuadraticTorque":
        law = spec.quadratic
        return cls(nominal_torque=law.nominal_torque, nominal_speed=law.nominal_speed, shaft=spec.shaft,
                   section=spec.name, reverses=law.direction == "reverses")

    @property
    def columns(self) -> dict:
        return {self.section: ("N*m", f"torque on shaft {self.shaft}, quadratic in its speed")}

    def torque(self, x):
        w = x.speed(self.shaft) / self.nominal_speed
        return self.nominal_torque * (w * jnp.abs(w) if self.reverses else w * w)

    def outputs(self, x) -> dict:
        return {self.section: self.torque(x)}

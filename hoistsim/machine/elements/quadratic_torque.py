"""A torque on a shaft of a drawn drivetrain quadratic in the shaft's speed (Modelica's
QuadraticSpeedDependentTorque)."""

from __future__ import annotations

import jax.numpy as jnp

from ._speed_law import AbstractSpeedLawTorque


class QuadraticTorque(AbstractSpeedLawTorque):
    """tau = tau_n (w / w_n)^2, positive in the shaft's positive sense: times sign(w) where its direction
    reverses with the turning (a fan's drag, tau_n < 0), the same both ways where it is fixed.  Smooth (w |w| has
    a continuous slope at rest), so no kink.  Its work on the shaft is a state and a work term of the ledger."""

    law = "quadratic"

    def torque(self, x):
        w = x.speed(self.shaft) / self.nominal_speed
        return self.nominal_torque * (w * jnp.abs(w) if self.reverses else w * w)

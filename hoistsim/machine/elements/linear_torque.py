"""A torque on a shaft of a drawn drivetrain linear in the shaft's speed (Modelica's LinearSpeedDependentTorque)."""

from __future__ import annotations

import jax.numpy as jnp

from ._speed_law import AbstractSpeedLawTorque


class LinearTorque(AbstractSpeedLawTorque):
    """tau = tau_n w / w_n, positive in the shaft's positive sense, where its direction reverses with the turning
    (a damper to the ground, tau_n < 0: smooth); tau_n |w| / w_n the same both ways where it is fixed, whose kink
    at rest is located (the shaft's speed through zero, either way: the observation ``<name>_at_rest``).  Its
    work on the shaft is a state and a work term of the ledger."""

    law = "linear"

    @property
    def observation_kinds(self) -> tuple:
        return () if self.reverses else (f"{self.section}_at_rest",)

    @property
    def crossings(self) -> tuple:
        return self.observation_kinds

    def observations(self, x) -> dict:
        return {} if self.reverses else {f"{self.section}_at_rest": x.speed(self.shaft)}

    def torque(self, x):
        w = x.speed(self.shaft) / self.nominal_speed
        return self.nominal_torque * (w if self.reverses else jnp.abs(w))

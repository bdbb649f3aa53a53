"""A torque on a shaft of a drawn drivetrain linear in the shaft's speed (Modelica's LinearSpeedDependentTorque)."""

from __future__ import annotations

import jax.numpy as jnp

from ..._pytree import static
from ._shaft_work import AbstractShaftWork


class LinearTorque(AbstractShaftWork):
    """tau = tau_n w / w_n, positive in the shaft's positive sense, where its direction reverses with the turning
    (a damper to the ground, tau_n < 0: smooth); tau_n |w| / w_n the same both ways where it is fixed, whose kink
    at rest is located (the shaft's speed through zero, either way: the observation ``<name>_at_rest``).  Its
    work on the shaft is a state and a work term of the ledger."""

    nominal_torque: object  # tau_n, N*m
    nominal_speed: object  # w_n, rad/s
    shaft: str = static("")
    section: str = static("")  # torque1, torque2, ... in the order of drivetrain.torques
    reverses: bool = static(True)  # its sign follows the speed's (Modelica's TorqueDirection = false)

    @classmethod
    def from_spec(cls, spec) -> "LinearTorque":
        law = spec.linear
        return cls(nominal_torque=law.nominal_torque, nominal_speed=law.nominal_speed, shaft=spec.shaft,
                   section=spec.name, reverses=law.direction == "reverses")

    @property
    def columns(self) -> dict:
        return {self.section: ("N*m", f"torque on shaft {self.shaft}, linear in its speed")}

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

    def outputs(self, x) -> dict:
        return {self.section: self.torque(x)}

"""A force against the load's motion, quadratic in its speed (Modelica's QuadraticSpeedDependentForce)."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..core.element import AbstractElement


class LoadDrag(AbstractElement):
    """F = F_n (v / v_n)^2 against the load's speed v (the load's ``drag``: a rolling resistance, the air's),
    acting on the shaft ``load`` (its speed in m/s, so the torque there is the force in N), whatever carries the
    load.  Smooth (v |v| has a continuous slope at rest).  Its heat is a state and a loss of the ledger."""

    nominal_force: object  # F_n, N
    nominal_speed: object  # v_n, m/s

    section: ClassVar[str] = "load_drag"
    ledger_kinds: ClassVar[dict] = {"load_drag_heat": "loss"}
    columns: ClassVar[dict] = {
        "load_drag_force": ("N", "force of the drag on the load, positive along its positive direction"),
        "load_drag_heat": ("J", "heat the drag on the load has made so far"),
    }

    @classmethod
    def from_spec(cls, spec) -> "LoadDrag":
        return cls(nominal_force=spec.drag.force, nominal_speed=spec.drag.speed)

    def force(self, x):
        v = x.speed("load") / self.nominal_speed
        return -self.nominal_force * v * jnp.abs(v)

    def torques(self, x) -> tuple:
        return (("load", self.force(x)),)

    def states(self) -> dict:
        return {"load_drag_heat": 0.0}

    def rates(self, x) -> dict:
        return {"load_drag_heat": -self.force(x) * x.speed("load")}

    def ledger(self, x) -> dict:
        return {"load_drag_heat": x.state("load_drag_heat")}

    def outputs(self, x) -> dict:
        return {"load_drag_force": self.force(x), "load_drag_heat": x.state("load_drag_heat")}

"""The ground under the load: it holds the load up, never down."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import STUCK, AbstractCoupling
from ._one_way import OneWayHold

# EN 13001-2's dynamic factor phi2 = phi2_min + beta2 * v_h by hoisting class: (phi2_min, beta2 [s/m])
HOISTING_CLASSES = {"HC1": (1.05, 0.17), "HC2": (1.10, 0.34), "HC3": (1.15, 0.51), "HC4": (1.20, 0.68)}


class Ground(OneWayHold, AbstractCoupling):
    """A one-way support under the load (a load's ``ground``, built from the load): a contact between the load
    and the ground (the load pressing
    down pushes it backwards: held without limit; a pull up meets no support).

    Resting (stuck) it holds any push down and none up: the load lifts off
    (``lift_off``) at the instant the rope pulls more than its weight.  In the
    air the two part (the coupling slips forwards, passing nothing) until the
    load comes down to where it started (its gap, the load's height, closes):
    it lands (``touch_down``) in a plastic impact, the core's momentum-keeping
    lock, and the kinetic energy that takes is the ledger's ``landing_loss``.
    With a rigid rope the load moves with the drum, and landing stops the drum
    and whatever turns with it.
    With a hoisting class, ``dynamic_factor_standard``: EN 13001-2's phi2 for
    the rope speed at the drum at lift-off, beside the simulated factor.
    """

    phi2_min: object  # the hoisting class's phi2,min (NaN without a class)
    beta2: object  # s/m
    classed: bool = static(False)  # a hoisting class is given: the standard's factor is a summary

    section: ClassVar[str] = "ground"
    impact_state: ClassVar[str] = "landing_loss"
    switch_names: ClassVar[dict] = {"lock": "touch_down", "unlock": "lift_off"}
    observes_slip_peak: ClassVar[bool] = False
    ledger_kinds: ClassVar[dict] = {"landing_loss": "loss"}
    columns: ClassVar[dict] = {
        "ground_force": ("N", "the ground's push up on the load (0 in the air)"),
        "load_on_ground": ("1", "1 while the load rests on the ground"),
    }

    @property
    def summaries(self) -> dict:
        out = {"lift_off_time": "s", "landing_loss": "J"}
        return {**out, "dynamic_factor_standard": "1"} if self.classed else out

    @classmethod
    def from_spec(cls, spec) -> "Ground":
        hoisting_class = spec.ground.hoisting_class
        classed = hoisting_class is not None
        phi2_min, beta2 = HOISTING_CLASSES[hoisting_class] if classed else (float("nan"), float("nan"))
        return cls(phi2_min=phi2_min, beta2=beta2, classed=classed)

    def joins(self) -> tuple:
        return ("load", None)

    def angles(self) -> tuple:
        return ("load",)  # the load's height (the mass load's position)

    def gap(self, x):
        return x.angle("load")

    def states(self) -> dict:
        return {"landing_loss": 0.0}

    def ledger(self, x) -> dict:
        return {"landing_loss": x.state("landing_loss")}

    def extremes(self, x) -> dict:
        aloft = x.mode("ground") != STUCK
        out = {"lift_off_time": ("first", aloft)}
        if self.classed:
            # v_h: the rope speed at the drum when the load leaves the ground
            out["dynamic_factor_standard"] = ("first_value", (aloft, self.phi2_min + self.beta2 * x.speed("rope_point")))
        return out

    def summary(self, x) -> dict:
        return {"landing_loss": x.state("landing_loss")}

    def outputs(self, x) -> dict:
        return {"ground_force": -x.coupling_torque("ground"),
                "load_on_ground": (x.mode("ground") == STUCK).astype(jnp.int8)}

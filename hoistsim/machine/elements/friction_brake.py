"""A friction brake on a shaft (the hoist's drum): holds up to its static torque, slips at its kinetic torque."""

from __future__ import annotations


import jax.numpy as jnp
import numpy as np

from ..core.element import OPEN
from ._shaft_hold import AbstractShaftHold
from ._slip_heat import AbstractSlipHeat


class FrictionBrake(AbstractSlipHeat, AbstractShaftHold):
    """A friction coupling of a shaft to the ground, closed until ``release_time`` and again from
    ``apply_time`` (never, when not given).

    Stuck while the torque it must hold stays within its static torque, slipping
    (either way) at its kinetic torque otherwise: a load lowered on the brake is
    slowed at T_k - M g R and stopped, a load too heavy for it runs down.  Its
    heat of slip (torque times drum speed) is a state and a loss of the ledger.
    Release and apply are scheduled: segment boundaries and the events
    ``<name>_release`` and ``<name>_apply``; its locks and unlocks are events
    named after it (the hoist's brake: ``brake_release``, ``brake``).
    """

    static_torque: object  # N*m, at its shaft
    kinetic_torque: object  # N*m
    apply_time: object  # s (inf: never closes again)

    @classmethod
    def from_spec(cls, spec) -> "FrictionBrake":
        kinetic = spec.static_torque if spec.kinetic_torque is None else spec.kinetic_torque
        return cls(static_torque=spec.static_torque, kinetic_torque=kinetic, release_time=spec.release_time,
                   apply_time=np.inf if spec.apply_time is None else spec.apply_time, shaft=spec.shaft,
                   section=spec.name)

    @property
    def heat_state(self) -> str:
        return f"{self.section}_energy"

    @property
    def event_kinds(self) -> tuple:
        return (self.release_event, f"{self.section}_apply")

    @property
    def summaries(self) -> dict:
        return {self.heat_state: "J"}

    @property
    def columns(self) -> dict:
        name = self.section
        return {**super().columns,
                f"{name}_mode": ("1", "0 holding, 1 slipping forwards (as the hoist's load rises), 2 slipping "
                                      "backwards (as it lowers), 3 open"),
                f"{name}_heat": ("J", f"energy dissipated in {name} so far (the summary's {name}_energy at the end)"),
                f"{name}_capacity": ("N*m", f"the most {name} holds: its static torque while closed, 0 while open")}

    def capacity(self, x):
        return self.static_torque

    def sliding_torque(self, x):
        return self.kinetic_torque

    def is_open(self, segment):
        return super().is_open(segment) & (segment.middle < self.apply_time)

    def boundaries(self) -> tuple:
        return (*super().boundaries(), self.apply_time)

    def boundary_events(self, t) -> tuple:
        return (*super().boundary_events(t), (f"{self.section}_apply", t == self.apply_time))

    def summary(self, x) -> dict:
        return {self.heat_state: x.state(self.heat_state)}

    def outputs(self, x) -> dict:
        name, mode = self.section, x.mode(self.section)
        return {**super().outputs(x), f"{name}_mode": mode.astype(jnp.int8), f"{name}_heat": x.state(self.heat_state),
                f"{name}_capacity": jnp.where(mode == OPEN, 0.0, self.static_torque)}

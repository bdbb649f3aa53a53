"""A friction brake on the drum shaft: holds up to its static torque, slips at its kinetic torque."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp
import numpy as np

from ..core.element import OPEN
from ._drum_hold import AbstractDrumHold
from ._slip_heat import AbstractSlipHeat


class FrictionBrake(AbstractSlipHeat, AbstractDrumHold):
    """A friction coupling of the drum shaft to the ground, closed until ``release_time`` and again from
    ``apply_time`` (never, when not given).

    Stuck while the torque it must hold stays within its static torque, slipping
    (either way) at its kinetic torque otherwise: a load lowered on the brake is
    slowed at T_k - M g R and stopped, a load too heavy for it runs down.  Its
    heat of slip (torque times drum speed) is a state and a loss of the ledger.
    Release and apply are scheduled: segment boundaries and the events
    ``brake_release`` and ``brake_apply``; its locks and unlocks are events
    named ``brake``.
    """

    static_torque: object  # N*m, at the drum shaft
    kinetic_torque: object  # N*m
    apply_time: object  # s (inf: never closes again)

    section: ClassVar[str] = "brake"
    heat_state: ClassVar[str] = "brake_energy"
    release_event: ClassVar[str] = "brake_release"
    event_kinds: ClassVar[tuple] = ("brake_release", "brake_apply")
    summaries: ClassVar[dict] = {"brake_energy": "J"}
    ledger_kinds: ClassVar[dict] = {"brake_energy": "loss"}
    columns: ClassVar[dict] = {
        "brake_torque": ("N*m", "torque the brake applies to the drum, positive holding the load up"),
        "brake_engaged": ("1", "1 while the brake holds the drum"),
        "brake_mode": ("1", "0 holding, 1 slipping as the load rises, 2 slipping as it lowers, 3 open"),
        "brake_heat": ("J", "energy dissipated in the brake so far (the summary's brake_energy at the end)"),
        "brake_capacity": ("N*m", "the most the brake holds: its static torque while closed, 0 while open"),
    }

    @classmethod
    def from_spec(cls, spec, scenario) -> "FrictionBrake":
        kinetic = spec.static_torque if spec.kinetic_torque is None else spec.kinetic_torque
        return cls(static_torque=spec.static_torque, kinetic_torque=kinetic, release_time=spec.release_time,
                   apply_time=np.inf if spec.apply_time is None else spec.apply_time)

    def capacity(self, x):
        return self.static_torque

    def sliding_torque(self, x):
        return self.kinetic_torque

    def is_open(self, segment):
        return super().is_open(segment) & (segment.middle < self.apply_time)

    def boundaries(self) -> tuple:
        return (*super().boundaries(), self.apply_time)

    def boundary_events(self, t) -> tuple:
        return (*super().boundary_events(t), ("brake_apply", t == self.apply_time))

    def summary(self, x) -> dict:
        return {"brake_energy": x.state("brake_energy")}

    def outputs(self, x) -> dict:
        mode = x.mode("brake")
        return {**super().outputs(x), "brake_mode": mode.astype(jnp.int8), "brake_heat": x.state("brake_energy"),
                "brake_capacity": jnp.where(mode == OPEN, 0.0, self.static_torque)}

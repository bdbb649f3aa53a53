"""The holding brake: keeps the drum still until it is released."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ._base import AbstractEffect, RowContext


class HoldingBrake(AbstractEffect):
    """Before ``release_time`` the drum shaft is held (its speed stays 0); after, it is free.

    The release is a scheduled discontinuity, so it is a segment boundary of the
    integration and an event ``brake_release`` in the events table.
    """

    release_time: object  # s

    section: ClassVar[str] = "brake"
    output_units: ClassVar[dict[str, str]] = {"brake_torque": "N*m", "brake_engaged": "1"}

    @classmethod
    def from_spec(cls, spec, scenario) -> "HoldingBrake":
        return cls(release_time=spec.release_time)

    def boundaries(self) -> tuple:
        return (self.release_time,)

    def holds_drum(self, t):
        return t < self.release_time

    def boundary_events(self, t) -> tuple:
        return (("brake_release", t == self.release_time),)

    def outputs(self, row: RowContext, drivetrain) -> dict:
        # Torque the brake applies at the drum shaft to hold it: what the clutch
        # does not carry of the load, brought back through the gear ratio.
        held = self.holds_drum(row.time)
        on_pinion = drivetrain.load_torque - row.clutch_torque
        return {
            "brake_torque": jnp.where(held, on_pinion * drivetrain.ratio, 0.0),
            "brake_engaged": held.astype(jnp.int8),
        }

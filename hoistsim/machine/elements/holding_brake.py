"""The holding brake: keeps the drum still until it is released."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ._drum_hold import AbstractDrumHold


class HoldingBrake(AbstractDrumHold):
    """A coupling of the drum shaft to the ground, stuck until ``release_time``, open after.

    It holds any torque (no capacity limit) and never slips.  The release is a
    scheduled discontinuity: a segment boundary of the integration and the
    event ``brake_release``.
    """

    section: ClassVar[str] = "brake"
    release_event: ClassVar[str] = "brake_release"
    can_slip: ClassVar[bool] = False
    reports_switches: ClassVar[bool] = False
    event_kinds: ClassVar[tuple] = ("brake_release",)
    columns: ClassVar[dict] = {
        "brake_torque": ("N*m", "torque the brake applies to the drum, positive holding the load up"),
        "brake_engaged": ("1", "1 while the brake holds the drum"),
    }

    @classmethod
    def from_spec(cls, spec, scenario) -> "HoldingBrake":
        return cls(release_time=spec.release_time)

    def capacity(self, x):
        return jnp.inf

    def sliding_torque(self, x):
        return 0.0

"""The holding brake: keeps the drum still until it is released."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..core.element import STUCK, AbstractCoupling
from ..core.panel import Panel, Phase, Trace


class HoldingBrake(AbstractCoupling):
    """A coupling of the drum shaft to the ground, stuck until ``release_time``, open after.

    It holds any torque (no capacity limit) and never slips.  The release is a
    scheduled discontinuity: a segment boundary of the integration and the
    event ``brake_release``.
    """

    release_time: object  # s

    section: ClassVar[str] = "brake"
    can_slip: ClassVar[bool] = False
    reports_switches: ClassVar[bool] = False
    event_kinds: ClassVar[tuple] = ("brake_release",)
    columns: ClassVar[dict] = {
        "brake_torque": ("N*m", "torque the brake applies to the drum, positive holding the load up"),
        "brake_engaged": ("1", "1 while the brake holds the drum"),
    }
    panels: ClassVar[tuple] = (Panel("brake", "brake torque [N*m]\n(at the drum)", 40,
                                     (Trace("holding the load up", "brake_torque"),), zero_line=True, height=0.8),)
    shading: ClassVar[tuple] = (Phase("brake holding", "brake_engaged", 1, "#8c510a", hatch="///"),)

    @classmethod
    def from_spec(cls, spec, scenario) -> "HoldingBrake":
        return cls(release_time=spec.release_time)

    def joins(self) -> tuple:
        return ("drum", None)

    def capacity(self, x):
        return jnp.inf

    def sliding_torque(self, x):
        return 0.0

    def is_open(self, segment):
        return segment.middle >= self.release_time

    def boundaries(self) -> tuple:
        return (self.release_time,)

    def boundary_events(self, t) -> tuple:
        return (("brake_release", t == self.release_time),)

    def outputs(self, x) -> dict:
        # The torque the coupling passes from the drum to the ground is what the
        # drum pushes on the brake; the brake pushes back with its opposite.
        return {"brake_torque": -x.coupling_torque("brake"),
                "brake_engaged": (x.mode("brake") == STUCK).astype(jnp.int8)}

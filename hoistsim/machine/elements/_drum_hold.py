"""What a brake and a pawl on the drum share: a coupling of the drum shaft to the ground, let go at a time."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..core.element import STUCK, AbstractCoupling


class AbstractDrumHold(AbstractCoupling):
    """Holds the drum shaft to the ground until ``release_time`` (inf: never let go), open after.

    The release is a scheduled discontinuity: a segment boundary and the event
    ``release_event``.  Its columns ``<section>_torque`` (what it applies to the
    drum, positive holding the load up) and ``<section>_engaged``.
    """

    release_time: object  # s

    release_event: ClassVar[str]

    def joins(self) -> tuple:
        return ("drum", None)

    def is_open(self, segment):
        return segment.middle >= self.release_time

    def boundaries(self) -> tuple:
        return (self.release_time,)

    def boundary_events(self, t) -> tuple:
        return ((self.release_event, t == self.release_time),)

    def outputs(self, x) -> dict:
        # The torque the coupling passes from the drum to the ground is what the
        # drum pushes on it; it pushes back with its opposite.
        return {f"{self.section}_torque": -x.coupling_torque(self.section),
                f"{self.section}_engaged": (x.mode(self.section) == STUCK).astype(jnp.int8)}

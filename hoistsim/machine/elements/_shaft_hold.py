"""What a brake and a pawl share: a coupling of a shaft to the ground, let go at a time."""

from __future__ import annotations

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import STUCK, AbstractCoupling


class AbstractShaftHold(AbstractCoupling):
    """Holds a shaft (the hoist's drum) to the ground until ``release_time`` (inf: never let go), open after.

    The release is a scheduled discontinuity: a segment boundary and the event ``<name>_release``.  Its
    columns ``<name>_torque`` (what it applies to the shaft, positive in the shaft's positive sense: on the
    hoist's drum, holding the load up) and ``<name>_engaged``.
    """

    release_time: object  # s
    shaft: str = static()
    section: str = static()  # its name (the hoist's: brake, ratchet)

    @property
    def release_event(self) -> str:
        return f"{self.section}_release"

    @property
    def event_kinds(self) -> tuple:
        return (self.release_event,)

    @property
    def columns(self) -> dict:
        return {f"{self.section}_torque": ("N*m", f"torque {self.section} applies to shaft {self.shaft}, positive in "
                                                  "its positive sense (on the hoist's drum: holding the load up)"),
                f"{self.section}_engaged": ("1", f"1 while {self.section} holds shaft {self.shaft}")}

    def joins(self) -> tuple:
        return (self.shaft, None)

    def is_open(self, segment):
        return segment.middle >= self.release_time

    def boundaries(self) -> tuple:
        return (self.release_time,)

    def boundary_events(self, t) -> tuple:
        return ((self.release_event, t == self.release_time),)

    def outputs(self, x) -> dict:
        # The torque the coupling passes from the shaft to the ground is what the
        # shaft pushes on it; it pushes back with its opposite.
        return {f"{self.section}_torque": -x.coupling_torque(self.section),
                f"{self.section}_engaged": (x.mode(self.section) == STUCK).astype(jnp.int8)}

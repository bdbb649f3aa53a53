"""A friction brake on a shaft that a drive's brake sequence releases and applies (a hoist's holding brake)."""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from ..._pytree import static
from ..core.element import STUCK
from .friction_brake import FrictionBrake


class OperatedBrake(FrictionBrake):
    """A friction brake closed until its drive's sequence releases it and closed again when the sequence applies
    it: its drive (a speed controller) counts, as states, the time since it proved its torque and the time since
    it commanded the brake closed; the brake is open while the first has passed its opening time and the second
    has not passed its closing time.  Closed, it holds up to its static torque and slips at its kinetic torque;
    open, it passes nothing.  Where each count passes its time is located as a switch is: the events
    ``<name>_release`` and ``<name>_apply``.
    """

    release_delay: object  # s: its opening time, from the drive's proof
    close_delay: object  # s: its closing time, from the drive's command
    drive: str = static("")  # the speed controller whose sequence works it

    @classmethod
    def from_spec(cls, spec) -> "OperatedBrake":
        kinetic = spec.static_torque if spec.kinetic_torque is None else spec.kinetic_torque
        return cls(static_torque=spec.static_torque, kinetic_torque=kinetic, release_time=np.inf, apply_time=np.inf,
                   release_delay=spec.resolved("release_delay"), close_delay=spec.resolved("close_delay"),
                   shaft=spec.shaft, section=spec.name, drive=spec.operated_by)

    @property
    def event_kinds(self) -> tuple:  # none scheduled: its drive's counts decide
        return ()

    @property
    def observation_kinds(self) -> tuple:
        return (f"{self.section}_opening", f"{self.section}_closing")

    @property
    def crossings(self) -> tuple:
        return self.observation_kinds

    @property
    def crossing_events(self) -> dict:
        # each count only rises: its crossing is the rising way's event (the falling way's never happens)
        opening, closing = self.observation_kinds
        return {opening: (self.release_event, self.release_event),
                closing: (f"{self.section}_apply", f"{self.section}_apply")}

    def observations(self, x) -> dict:
        opening, closing = self.observation_kinds
        return {opening: x.state(f"{self.drive}_release_count") - self.release_delay,
                closing: x.state(f"{self.drive}_close_count") - self.close_delay}

    def closed(self, x):
        """1 while it holds (before its release, after its apply), 0 while open."""
        released = x.state(f"{self.drive}_release_count") >= self.release_delay
        applied = x.state(f"{self.drive}_close_count") >= self.close_delay
        return jnp.where(released & ~applied, 0.0, 1.0)

    def capacity(self, x):
        return self.static_torque * self.closed(x)

    def sliding_torque(self, x):
        return self.kinetic_torque * self.closed(x)

    def is_open(self, segment):
        return False

    def boundaries(self) -> tuple:
        return ()

    def boundary_events(self, t) -> tuple:
        return ()

    def outputs(self, x) -> dict:
        # open, it holds nothing even where nothing pulls on it (stuck at no torque): not engaged
        name = self.section
        engaged = (x.mode(name) == STUCK) & (self.closed(x) > 0.0)
        return {**super().outputs(x), f"{name}_capacity": self.capacity(x), f"{name}_engaged": engaged.astype(jnp.int8)}

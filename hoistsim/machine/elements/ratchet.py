"""A ratchet (pawl) on the drum shaft: the drum may turn to lift, never to lower."""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from ._drum_hold import AbstractDrumHold
from ._one_way import OneWayHold


class Ratchet(OneWayHold, AbstractDrumHold):
    """A one-way coupling of the drum shaft to the ground, until ``release_time`` lifts the pawl.

    Stuck, it holds any torque that would lower the load and none that would
    lift it: a drive that lifts frees it (it "slips" forwards, passing no
    torque, the pawl clicking over the teeth) and the drum coming back to rest
    catches it again, exactly where its speed falls through zero.  Its locks and
    unlocks are events named ``ratchet``; the release a boundary and the event
    ``ratchet_release``.
    """

    section: ClassVar[str] = "ratchet"
    release_event: ClassVar[str] = "ratchet_release"
    observes_slip_peak: ClassVar[bool] = False
    event_kinds: ClassVar[tuple] = ("ratchet_release",)
    columns: ClassVar[dict] = {
        "ratchet_torque": ("N*m", "torque the pawl applies to the drum, positive holding the load up"),
        "ratchet_engaged": ("1", "1 while the pawl holds the drum"),
    }

    @classmethod
    def from_spec(cls, spec, scenario) -> "Ratchet":
        return cls(release_time=np.inf if spec.release_time is None else spec.release_time)

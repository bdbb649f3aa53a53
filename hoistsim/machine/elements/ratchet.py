"""A ratchet (pawl) on a shaft (the hoist's drum): the shaft may turn forwards (to lift), never backwards."""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from ._one_way import OneWayHold
from ._shaft_hold import AbstractShaftHold


class Ratchet(OneWayHold, AbstractShaftHold):
    """A one-way coupling of a shaft to the ground, until ``release_time`` lifts the pawl.

    Stuck, it holds any torque that would turn the shaft backwards (lower the load)
    and none that would turn it forwards: a drive that lifts frees it (it "slips"
    forwards, passing no torque, the pawl clicking over the teeth) and the shaft
    coming back to rest catches it again, exactly where its speed falls through
    zero.  Its locks and unlocks are events named after it (the hoist's
    ``ratchet``); the release a boundary and the event ``<name>_release``.
    """

    observes_slip_peak: ClassVar[bool] = False

    @classmethod
    def from_spec(cls, spec) -> "Ratchet":
        return cls(release_time=np.inf if spec.release_time is None else spec.release_time, shaft=spec.shaft,
                   section=spec.name)

"""A shaft driven at an acceleration given as a signal of time (Modelica's Rotational.Sources.Accelerate)."""

from __future__ import annotations

from ._motion_source import AbstractMotionSource
from ._signal import signal_at


class AccelerationSource(AbstractMotionSource):
    """Holds its shaft's acceleration at a_ref(t), from the speed the shaft starts with (a shaft's ``speed``, a
    mass's ``velocity``)."""

    def motion(self, x) -> tuple:
        return None, signal_at(self, x, "reference")

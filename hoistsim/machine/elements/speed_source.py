"""A shaft driven at a speed given as a signal of time (Modelica's Rotational.Sources.Speed)."""

from __future__ import annotations

import math

from ._motion_source import AbstractMotionSource
from ._signal import signal_at, signal_derivatives, signal_start


class SpeedSource(AbstractMotionSource):
    """Holds its shaft at the speed w_ref(t): exactly (the shaft's acceleration the signal's slope), or, with a
    filter frequency f_crit, through a first-order lag, w' = (w_ref - w) 2 pi f_crit, w starting at w_ref(0) (the
    filtered speed the state ``<name>_filtered_speed``)."""

    @property
    def filtered_state(self) -> str:
        return f"{self.section}_filtered_speed"

    def states(self) -> dict:
        filtered = {} if self.filter_frequency is None else {self.filtered_state: signal_start(self, "reference")}
        return super().states() | filtered

    def _filtered_rate(self, x):
        return (signal_at(self, x, "reference") - x.state(self.filtered_state)) * 2.0 * math.pi * self.filter_frequency

    def rates(self, x) -> dict:
        filtered = {} if self.filter_frequency is None else {self.filtered_state: self._filtered_rate(x)}
        return super().rates(x) | filtered

    def motion(self, x) -> tuple:
        if self.filter_frequency is None:
            return tuple(signal_derivatives(self, x, "reference", 1))
        return x.state(self.filtered_state), self._filtered_rate(x)

"""A shaft driven at a speed given as a signal of time (Modelica's Rotational.Sources.Speed)."""

from __future__ import annotations

import math

from ..._pytree import static
from ._motion_source import AbstractMotionSource
from ._signal import (
    signal_at,
    signal_derivatives,
    signal_fields,
    signal_start,
    signal_tables,
)


class SpeedSource(AbstractMotionSource):
    """Holds its shaft at the speed w_ref(t): exactly (the shaft's acceleration the signal's slope), or, with a
    filter frequency f_crit, through a first-order lag, w' = (w_ref - w) 2 pi f_crit, w starting at w_ref(0) (the
    filtered speed the state ``<name>_filtered_speed``)."""

    speed_times: object  # s
    speed_values: object  # rad/s
    speed_amplitudes: object  # rad/s
    speed_frequencies: object  # Hz
    speed_phases: object  # rad
    speed_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    speed_envelope_values: object = None
    filter_frequency: object = None  # Hz (None: exactly)
    on_line: bool = static(False)  # it drives a mass (m, m/s, m/s^2; a force)
    shaft: str = static("")
    section: str = static("")  # its key in drivetrain.motion_sources

    @classmethod
    def from_spec(cls, spec) -> "SpeedSource":
        return cls(**signal_fields(spec.reference, "speed"),
                   filter_frequency=spec.filter_frequency, on_line=spec.resolved("on_line"), shaft=spec.shaft,
                   section=spec.name)

    @property
    def filtered_state(self) -> str:
        return f"{self.section}_filtered_speed"

    def tables(self) -> dict:
        return signal_tables(self, "speed")

    def states(self) -> dict:
        filtered = {} if self.filter_frequency is None else {self.filtered_state: signal_start(self, "speed")}
        return super().states() | filtered

    def _filtered_rate(self, x):
        return (signal_at(self, x, "speed") - x.state(self.filtered_state)) * 2.0 * math.pi * self.filter_frequency

    def rates(self, x) -> dict:
        filtered = {} if self.filter_frequency is None else {self.filtered_state: self._filtered_rate(x)}
        return super().rates(x) | filtered

    def motion(self, x) -> tuple:
        if self.filter_frequency is None:
            return tuple(signal_derivatives(self, x, "speed", 1))
        return x.state(self.filtered_state), self._filtered_rate(x)

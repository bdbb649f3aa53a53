"""A shaft driven to an angle given as a signal of time (Modelica's Rotational.Sources.Position)."""

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

# Modelica's Position filter, phi_ref / (1 + (a/w_c) s + (b/w_c^2) s^2): a Bessel filter's coefficients
BESSEL_S, BESSEL_S2 = 1.3617, 0.6180


class AngleSource(AbstractMotionSource):
    """Holds its shaft at the angle phi_ref(t), the shaft starting there: exactly (its speed the signal's slope,
    which jumps where a table kinks, its acceleration the signal's second derivative), or, with a filter
    frequency f_crit, through Modelica's second-order filter, phi'' = ((phi_ref - phi) w_c - a phi') w_c / b with
    w_c = 2 pi f_crit, starting at rest (the filtered angle and speed the states ``<name>_filtered_angle`` and
    ``<name>_filtered_speed``).  The shaft's angle is an output, ``<shaft>_angle``."""

    angle_times: object  # s
    angle_values: object  # rad
    angle_amplitudes: object  # rad
    angle_frequencies: object  # Hz
    angle_phases: object  # rad
    angle_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    angle_envelope_values: object = None
    filter_frequency: object = None  # Hz (None: exactly)
    on_line: bool = static(False)  # it drives a mass (m, m/s, m/s^2; a force)
    shaft: str = static("")
    section: str = static("")  # its key in drivetrain.motion_sources

    @classmethod
    def from_spec(cls, spec) -> "AngleSource":
        return cls(**signal_fields(spec.reference, "angle"),
                   filter_frequency=spec.filter_frequency, on_line=spec.resolved("on_line"), shaft=spec.shaft,
                   section=spec.name)

    @property
    def filtered_states(self) -> tuple:
        return f"{self.section}_filtered_angle", f"{self.section}_filtered_speed"

    def tables(self) -> dict:
        return signal_tables(self, "angle")

    def angles(self) -> tuple:
        return (self.shaft,)

    def angle_starts(self) -> dict:
        return {self.shaft: signal_start(self, "angle")}

    def states(self) -> dict:
        angle, speed = self.filtered_states
        filtered = {} if self.filter_frequency is None else {angle: signal_start(self, "angle"), speed: 0.0}
        return super().states() | filtered

    def _filtered_acceleration(self, x):
        angle, speed = (x.state(name) for name in self.filtered_states)
        crossover = 2.0 * math.pi * self.filter_frequency
        return ((signal_at(self, x, "angle") - angle) * crossover - BESSEL_S * speed) * crossover / BESSEL_S2

    def rates(self, x) -> dict:
        if self.filter_frequency is None:
            return super().rates(x)
        angle, speed = self.filtered_states
        return super().rates(x) | {angle: x.state(speed), speed: self._filtered_acceleration(x)}

    def motion(self, x) -> tuple:
        if self.filter_frequency is None:
            return tuple(signal_derivatives(self, x, "angle", 2)[1:])
        return x.state(self.filtered_states[1]), self._filtered_acceleration(x)

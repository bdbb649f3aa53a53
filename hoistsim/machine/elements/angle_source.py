"""A shaft driven to an angle given as a signal of time (Modelica's Rotational.Sources.Position)."""

from __future__ import annotations

import math

from ._motion_source import AbstractMotionSource
from ._signal import signal_at, signal_derivatives, signal_start

# Modelica's Position filter, phi_ref / (1 + (a/w_c) s + (b/w_c^2) s^2): a Bessel filter's coefficients
BESSEL_S, BESSEL_S2 = 1.3617, 0.6180


class AngleSource(AbstractMotionSource):
    """Holds its shaft at the angle phi_ref(t), the shaft starting there: exactly (its speed the signal's slope,
    which jumps where a table kinks, its acceleration the signal's second derivative), or, with a filter
    frequency f_crit, through Modelica's second-order filter, phi'' = ((phi_ref - phi) w_c - a phi') w_c / b with
    w_c = 2 pi f_crit, starting at rest (the filtered angle and speed the states ``<name>_filtered_angle`` and
    ``<name>_filtered_speed``).  The shaft's angle is an output, ``<shaft>_angle``."""

    @property
    def filtered_states(self) -> tuple:
        return f"{self.section}_filtered_angle", f"{self.section}_filtered_speed"

    def angles(self) -> tuple:
        return (self.shaft,)

    def angle_starts(self) -> dict:
        return {self.shaft: signal_start(self, "reference")}

    def states(self) -> dict:
        angle, speed = self.filtered_states
        filtered = {} if self.filter_frequency is None else {angle: signal_start(self, "reference"), speed: 0.0}
        return super().states() | filtered

    def _filtered_acceleration(self, x):
        angle, speed = (x.state(name) for name in self.filtered_states)
        crossover = 2.0 * math.pi * self.filter_frequency
        return ((signal_at(self, x, "reference") - angle) * crossover - BESSEL_S * speed) * crossover / BESSEL_S2

    def rates(self, x) -> dict:
        if self.filter_frequency is None:
            return super().rates(x)
        angle, speed = self.filtered_states
        return super().rates(x) | {angle: x.state(speed), speed: self._filtered_acceleration(x)}

    def motion(self, x) -> tuple:
        if self.filter_frequency is None:
            return tuple(signal_derivatives(self, x, "reference", 2)[1:])
        return x.state(self.filtered_states[1]), self._filtered_acceleration(x)

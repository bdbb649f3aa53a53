"""A shaft driven at an acceleration given as a signal of time (Modelica's Rotational.Sources.Accelerate)."""

from __future__ import annotations

from ..._pytree import static
from ._motion_source import AbstractMotionSource
from ._signal import signal_at, signal_fields, signal_tables


class AccelerationSource(AbstractMotionSource):
    """Holds its shaft's acceleration at a_ref(t), from the speed the shaft starts with (its ``speed`` key)."""

    acceleration_times: object  # s
    acceleration_values: object  # rad/s^2
    acceleration_amplitudes: object  # rad/s^2
    acceleration_frequencies: object  # Hz
    acceleration_phases: object  # rad
    acceleration_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    acceleration_envelope_values: object = None
    on_line: bool = static(False)  # it drives a mass (m, m/s, m/s^2; a force)
    shaft: str = static("")
    section: str = static("")  # its key in drivetrain.motion_sources

    @classmethod
    def from_spec(cls, spec) -> "AccelerationSource":
        return cls(**signal_fields(spec.reference, "acceleration"), on_line=spec.resolved("on_line"),
                   shaft=spec.shaft, section=spec.name)

    def tables(self) -> dict:
        return signal_tables(self, "acceleration")

    def motion(self, x) -> tuple:
        return None, signal_at(self, x, "acceleration")

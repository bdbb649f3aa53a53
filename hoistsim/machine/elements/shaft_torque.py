"""An external torque on a shaft of a drawn drivetrain: a signal of time."""

from __future__ import annotations

from ..._pytree import static
from ._shaft_work import AbstractShaftWork
from ._signal import harmonics_step, signal_at, signal_fields, signal_tables


class ShaftTorque(AbstractShaftWork):
    """A torque on a shaft, positive in its positive sense: a constant, a table of time (its knots are
    segment boundaries) or an offset plus harmonics in time.  Its work on the shaft is a state and a
    work term of the energy ledger; the torque is the output named after it."""

    torque_times: object  # s
    torque_values: object  # N*m
    torque_amplitudes: object  # N*m
    torque_frequencies: object  # Hz
    torque_phases: object  # rad
    torque_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    torque_envelope_values: object = None
    shaft: str = static("")
    section: str = static("")  # torque1, torque2, ... in the order of drivetrain.torques

    @classmethod
    def from_spec(cls, spec) -> ShaftTorque:
        return cls(**signal_fields(spec.torque, "torque"), shaft=spec.shaft, section=spec.name)

    @property
    def columns(self) -> dict:
        return {self.section: ("N*m", f"external torque on shaft {self.shaft}")}

    def tables(self) -> dict:
        return signal_tables(self, "torque")

    def torque(self, x):
        return signal_at(self, x, "torque")

    def longest_step(self):
        return harmonics_step(self, "torque")

    def outputs(self, x) -> dict:
        return {self.section: self.torque(x)}

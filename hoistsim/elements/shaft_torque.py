"""An external torque on a shaft of a drawn drivetrain: a signal of time."""

from __future__ import annotations

from .._pytree import static
from ..core.element import AbstractElement
from ._signal import harmonics_at


class ShaftTorque(AbstractElement):
    """A torque on a shaft, positive in its positive sense: a constant, a table of time (its knots are
    segment boundaries) or an offset plus harmonics in time.  Its work on the shaft is a state and a
    work term of the energy ledger; the torque is the output named after it."""

    torque_times: object  # s
    torque_values: object  # N*m
    torque_amplitudes: object  # N*m
    torque_frequencies: object  # Hz
    torque_phases: object  # rad
    shaft: str = static("")
    section: str = static("")  # torque1, torque2, ... in the order of drivetrain.torques

    @property
    def columns(self) -> dict:
        return {self.section: ("N*m", f"external torque on shaft {self.shaft}")}

    @property
    def ledger_kinds(self) -> dict:
        return {f"{self.section}_work": "work"}

    def tables(self) -> dict:
        return {f"{self.section}.torque": ("torque_times", "torque_values")}

    def torque(self, x):
        return x.table(f"{self.section}.torque") + harmonics_at(x.t, self.torque_amplitudes, self.torque_frequencies,
                                                                self.torque_phases)

    def torques(self, x) -> tuple:
        return ((self.shaft, self.torque(x)),)

    def states(self) -> dict:
        return {f"{self.section}_work": 0.0}

    def rates(self, x) -> dict:
        return {f"{self.section}_work": self.torque(x) * x.speed(self.shaft)}

    def ledger(self, x) -> dict:
        return {f"{self.section}_work": x.state(f"{self.section}_work")}

    def outputs(self, x) -> dict:
        return {self.section: self.torque(x)}

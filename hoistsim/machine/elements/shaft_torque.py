"""An external torque on a shaft of a drawn drivetrain: a signal of time."""

from __future__ import annotations

from ..._pytree import static
from ._shaft_work import AbstractShaftWork
from ._signal import harmonics_at


class ShaftTorque(AbstractShaftWork):
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

    def tables(self) -> dict:
        return {f"{self.section}.torque": ("torque_times", "torque_values")}

    def torque(self, x):
        return x.table(f"{self.section}.torque") + harmonics_at(x.t, self.torque_amplitudes, self.torque_frequencies,
                                                                self.torque_phases)

    def outputs(self, x) -> dict:
        return {self.section: self.torque(x)}

    # A drawn part: Drivetrain.from_spec builds it with its constructor (its name is its place in
    # drivetrain.torques), not the registry from a section of its own; it takes (spec, scenario) once the
    # registry builds drawn parts too.
    @classmethod
    def from_spec(cls, spec, scenario) -> ShaftTorque:
        raise TypeError("an external torque is built by its drivetrain (Drivetrain.from_spec), not from a section "
                        "of its own")

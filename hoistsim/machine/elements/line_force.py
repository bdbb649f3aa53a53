"""An external force on a mass on a line: a signal of time (Modelica's Translational.Sources.Force)."""

from __future__ import annotations

from ._signal import signal_fields
from .shaft_torque import ShaftTorque


class LineForce(ShaftTorque):
    """A force on a mass, positive in the line's positive sense: a torque on a shaft's law in N and m/s (its
    work on the mass a state and a work term of the ledger); the force is the output named after it."""

    @classmethod
    def from_spec(cls, spec) -> "LineForce":
        return cls(**signal_fields(spec.force, "torque"), shaft=spec.mass, section=spec.name)

    @property
    def columns(self) -> dict:
        return {self.section: ("N", f"external force on mass {self.shaft}")}

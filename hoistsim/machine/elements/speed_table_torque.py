"""A torque on a shaft of a drawn drivetrain given as a table of the shaft's speed."""

from __future__ import annotations

import numpy as np

from ..._pytree import static
from ._knots import interpolate, knots_passed
from ._shaft_work import AbstractShaftWork

class SpeedTableTorque(AbstractShaftWork):
    """A torque on a shaft, positive in its positive sense, piecewise linear in the shaft's speed between the
    rows of a table [speed, torque] (speeds rising) and held at the first and last rows' torques beyond them.
    Each row's speed is a kink of the torque in the state: no step straddles one (``kinks``), as no step
    straddles a table of time's knot.  Its work on the shaft is a state and a work term of the energy ledger;
    the torque is the output named after it."""

    table_speeds: object  # rad/s, rising, at least two
    table_torques: object  # N*m
    shaft: str = static("")
    section: str = static("")  # torque1, torque2, ... in the order of drivetrain.torques

    @classmethod
    def from_spec(cls, spec) -> "SpeedTableTorque":
        speeds, torques = zip(*spec.torque_by_speed)
        return cls(table_speeds=np.asarray(speeds, float), table_torques=np.asarray(torques, float),
                   shaft=spec.shaft, section=spec.name)

    @property
    def columns(self) -> dict:
        return {self.section: ("N*m", f"torque on shaft {self.shaft}, a table of its speed")}

    def torque(self, x):
        return interpolate(x.speed(self.shaft), self.table_speeds, self.table_torques)

    def kink_names(self) -> tuple:
        return ("speed_knots",)

    def kinks(self, x) -> dict:
        return {"speed_knots": knots_passed(x.speed(self.shaft), self.table_speeds)}

    def outputs(self, x) -> dict:
        return {self.section: self.torque(x)}


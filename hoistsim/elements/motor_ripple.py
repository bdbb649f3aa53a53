"""A torque ripple of the motor: added to its characteristic, periodic in the motor angle."""

from __future__ import annotations

from typing import ClassVar

from ._ripple import AbstractRipple


class MotorRipple(AbstractRipple):
    """motor.ripple: the ripple of an engine's torque (a period of 720 deg for a four-stroke one).

    Reads the motor angle (so the scene keeps it as a state), adds its torque on
    the motor shaft, and counts its work in the ledger.
    """

    section: ClassVar[str] = "motor.ripple"
    ledger_kinds: ClassVar[dict] = {"motor_ripple_work": "work"}
    columns: ClassVar[dict] = {"ripple_torque": ("N*m", "motor torque ripple, added to the characteristic")}

    @classmethod
    def from_spec(cls, spec, scenario) -> "MotorRipple":
        return cls(**cls.fields_from(spec))

    def angles(self) -> tuple:
        return ("motor",)

    def kinks(self, x) -> dict:
        return {"knots": self.knots_passed(x.angle("motor"))} if self.kink_names() else {}

    def torques(self, x) -> tuple:
        return (("motor", self.torque_at(x.angle("motor"))),)

    def ledger(self, x) -> dict:
        return {"motor_ripple_work": self.work_to(x.angle("motor"))}

    def outputs(self, x) -> dict:
        return {"ripple_torque": self.torque_at(x.angle("motor"))}

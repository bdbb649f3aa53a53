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
    shaft: ClassVar[str] = "motor"
    direction: ClassVar[float] = 1.0
    work_term: ClassVar[str] = "motor_ripple_work"
    ledger_kinds: ClassVar[dict] = {"motor_ripple_work": "work"}
    column: ClassVar[str] = "ripple_torque"
    columns: ClassVar[dict] = {"ripple_torque": ("N*m", "motor torque ripple, added to the characteristic")}

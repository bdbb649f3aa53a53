"""A torque ripple of a motor: added to its characteristic, periodic in its shaft's angle."""

from __future__ import annotations

from typing import ClassVar

from ._ripple import AbstractRipple


class MotorRipple(AbstractRipple):
    """A motor's ``ripple``: the ripple of an engine's torque (a period of 720 deg for a four-stroke one).

    Reads its shaft's angle (so the scene keeps it as a state), adds its torque on the shaft, and counts its
    work in the ledger (``<motor>_ripple_work``); its column ``<motor>_ripple_torque`` (the hoist's
    ``ripple_torque``).
    """

    key: ClassVar[str] = "ripple"
    direction: ClassVar[float] = 1.0
    work_pattern: ClassVar[str] = "{name}_ripple_work"
    column_pattern: ClassVar[str] = "{name}_ripple_torque"
    meaning: ClassVar[str] = "motor torque ripple, added to the characteristic"

    @classmethod
    def from_spec(cls, spec) -> "MotorRipple":
        return cls.of_part(spec.ripple, spec.shaft, spec)

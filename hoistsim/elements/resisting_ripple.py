"""A resisting torque ripple on the drum: periodic in the drum angle, against the lift."""

from __future__ import annotations

from typing import ClassVar

from ._ripple import AbstractRipple


class ResistingRipple(AbstractRipple):
    """drum.resisting_ripple: a resisting torque that varies over each turn of the drum.

    Reads the drum angle, acts on the drum shaft against the lift (its torque
    M_r(theta) resists where positive), and counts its (negative) work in the ledger.
    """

    section: ClassVar[str] = "drum.resisting_ripple"
    ledger_kinds: ClassVar[dict] = {"resisting_ripple_work": "work"}
    columns: ClassVar[dict] = {"resisting_ripple_torque": ("N*m", "resisting torque ripple on the drum shaft, "
                                                                  "positive against the lift")}

    @classmethod
    def from_spec(cls, spec, scenario) -> "ResistingRipple":
        return cls(**cls.fields_from(spec))

    def angles(self) -> tuple:
        return ("drum",)

    def kinks(self, x) -> dict:
        return {"knots": self.knots_passed(x.angle("drum"))} if self.kink_names() else {}

    def torques(self, x) -> tuple:
        return (("drum", -self.torque_at(x.angle("drum"))),)

    def ledger(self, x) -> dict:
        return {"resisting_ripple_work": -self.work_to(x.angle("drum"))}

    def outputs(self, x) -> dict:
        return {"resisting_ripple_torque": self.torque_at(x.angle("drum"))}

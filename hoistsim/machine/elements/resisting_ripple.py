"""A resisting torque ripple on a shaft (the hoist's drum): periodic in its angle, against its turning."""

from __future__ import annotations

from typing import ClassVar

from ._ripple import AbstractRipple


class ResistingRipple(AbstractRipple):
    """A shaft's ``resisting_ripple`` (the hoist's ``drum.resisting_ripple``): a resisting torque that varies
    over each turn.

    Reads the shaft's angle, acts on it against its positive turning (the lift, on the hoist's drum: its
    torque M_r(theta) resists where positive), and counts its (negative) work in the ledger.
    """

    key: ClassVar[str] = "resisting_ripple"
    direction: ClassVar[float] = -1.0
    work_pattern: ClassVar[str] = "{name}_resisting_ripple_work"
    column_pattern: ClassVar[str] = "{name}_resisting_ripple_torque"
    meaning: ClassVar[str] = "resisting torque ripple on shaft {shaft}, positive against its turning"

    @classmethod
    def from_spec(cls, spec) -> "ResistingRipple":
        return cls.of_part(spec.resisting_ripple, spec.name, spec)

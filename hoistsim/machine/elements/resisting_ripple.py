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
    shaft: ClassVar[str] = "drum"
    direction: ClassVar[float] = -1.0
    work_term: ClassVar[str] = "resisting_ripple_work"
    ledger_kinds: ClassVar[dict] = {"resisting_ripple_work": "work"}
    column: ClassVar[str] = "resisting_ripple_torque"
    columns: ClassVar[dict] = {"resisting_ripple_torque": ("N*m", "resisting torque ripple on the drum shaft, "
                                                                  "positive against the lift")}

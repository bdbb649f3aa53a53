"""A hard stop at the high end of a mass's travel (``drivetrain.stops.<name>.upper``)."""

from __future__ import annotations

from typing import ClassVar

from ._end_stop import AbstractEndStop


class UpperStop(AbstractEndStop):
    """The mass's centre stops at ``position`` going up the line (its speed positive): pushed forwards into the
    stop it is held, pushed backwards it leaves."""

    side: ClassVar[float] = -1.0
    end: ClassVar[str] = "upper"

"""A hard stop at the low end of a mass's travel (``drivetrain.stops.<name>.lower``)."""

from __future__ import annotations

from typing import ClassVar

from ._end_stop import AbstractEndStop


class LowerStop(AbstractEndStop):
    """The mass's centre stops at ``position`` coming down the line (its speed negative): pushed backwards into
    the stop it is held, pushed forwards it leaves."""

    side: ClassVar[float] = 1.0
    end: ClassVar[str] = "lower"

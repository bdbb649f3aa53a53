"""What an element shows in the figures: panels of its columns, shaded phases, summary panels.

Plain descriptions, no matplotlib: an element lists them as class attributes
(``panels``, ``shading``, ``summary_panels``) and the plotting code draws those
whose columns a results file holds, so a part the scene does not name draws
nothing and a new part draws itself without a list in the plotting code.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

RPM = 30.0 / math.pi  # rad/s -> rpm


@dataclass(frozen=True)
class Trace:
    """One curve of a panel: a column (or a quantity made from columns), in the panel's units.

    ``value(run)`` makes the quantity from the run's columns (a mapping of
    names to arrays, with ``run["parameters"]`` the resolved scenario); absent,
    the column itself.  ``needs`` lists the columns it reads (``column`` when
    empty): a trace is drawn only where the file holds them.  A ``limit`` (a
    capacity) is drawn thin and dotted, and left out of a family of many runs.
    ``marks`` are observation kinds marked on the curve where they happened
    (a turnaround, a lock); ``marks_of`` keeps those of one element (its
    section: the locks of this coupling, not another's).
    """

    label: str
    column: str
    value: Callable | None = None
    needs: tuple[str, ...] = ()
    style: str = "-"
    limit: bool = False
    marks: tuple[str, ...] = ()
    marks_of: str | None = None

    def columns(self) -> tuple[str, ...]:
        return self.needs or (self.column,)

    def of(self, run):
        return run[self.column] if self.value is None else self.value(run)


@dataclass(frozen=True)
class Panel:
    """A panel of the run figure.  Panels of the same ``name`` from several elements are one panel.

    ``order`` places it from the top; ``scale`` turns SI into the units of
    ``ylabel``; ``zero_line`` draws the axis at zero (a sign that matters);
    ``right_axis`` is (label, factor(parameters)) for a second scale of the same
    curves (the speed of a shaft turning at a fixed ratio to the one drawn).
    """

    name: str
    ylabel: str
    order: int
    traces: tuple[Trace, ...]
    scale: float = 1.0
    zero_line: bool = False
    height: float = 1.0
    right_axis: tuple[str, Callable] | None = None


@dataclass(frozen=True)
class Phase:
    """Where a mode column equals ``value``, the run figure shades every panel (one run only)."""

    label: str
    column: str
    value: int
    colour: str
    hatch: str | None = None


@dataclass(frozen=True)
class SummaryPanel:
    """A summary value against the swept value, in the sweep's summary figure.

    ``partial`` names what the value means for a run that never locks (heat up
    to the end of the run, say): such points are drawn open and the legend says so.
    """

    name: str
    ylabel: str
    order: int
    scale: float = 1.0
    zero_line: bool = False
    partial: str | None = None
    offset: float = 0.0  # added after the scale: kelvin to degrees Celsius
    # a line across the panel: (its label, the dotted scenario key that gives it in SI; none where the
    # scenario does not give it, nor where that key is swept: the line would be one run's)
    limit: tuple[str, str] | None = None
    # another summary answering the same question, drawn beside it: (its label, its name)
    beside: tuple[str, str] | None = None


@dataclass(frozen=True)
class Outcome:
    """A kind of run the summary figure marks apart (never locks; never slips), by its summary row."""

    label: str
    applies: Callable[[dict], bool]
    colour: str
    marker: str


def speed_panel(*traces: Trace, right_axis=None) -> Panel:
    """The shaft-speed panel, on top: each element that turns a shaft adds its curve to it."""
    return Panel("speed", "shaft speed [rpm]", 0, traces, scale=RPM, height=1.5, right_axis=right_axis)

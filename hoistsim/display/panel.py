"""What a part shows in the figures: panels of its columns, shaded phases, summary panels, its headline.

Plain descriptions, no matplotlib and no JAX: each kind of part lists them in a :class:`Display`
(one module of this folder each) and the figures draw those whose columns a results file holds,
so a part the scene does not name draws nothing and a new part draws itself without a list in the
plotting code.
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
    section: the locks of this coupling, not another's).  ``lowest`` names the
    curve's lowest point, marked once where the curve goes below zero (a load
    that ran back below its start): the run's own minimum, wherever it lies (the
    end of a run still falling), not each turn of a ringing.
    """

    label: str
    column: str
    value: Callable | None = None
    needs: tuple[str, ...] = ()
    style: str = "-"
    limit: bool = False
    marks: tuple[str, ...] = ()
    marks_of: str | None = None
    lowest: str | None = None

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
    to the end of the run, say), ``partial_of`` the summary that says it never
    locked: such points are drawn open and the legend says so.
    """

    name: str
    ylabel: str
    order: int
    scale: float = 1.0
    zero_line: bool = False
    partial: str | None = None
    partial_of: str | None = None  # the summary that is NaN in a run whose value is partial (its lock-up time)
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


def drawn_parts(run: dict, kind: str) -> dict | list:
    """A run's drawn parts of a kind (its ``parameters``' drivetrain.<kind>, a hoist's none): empty where none."""
    return ((run.get("parameters") or {}).get("drivetrain") or {}).get(kind) or {}


def on_line(run: dict, *sides: str) -> bool:
    """Whether a part joins masses (on a line: forces in N, speeds in m/s), by the bodies it names: the drawn
    masses, and the drawn load (a mass named load)."""
    masses = [*drawn_parts(run, "masses"), *(["load"] if drawn_parts(run, "load") else [])]
    return any(side in masses for side in sides)


def speed_panel(*traces: Trace, right_axis=None) -> Panel:
    """The shaft-speed panel, on top: each element that turns a shaft adds its curve to it."""
    return Panel("speed", "shaft speed [rpm]", 0, traces, scale=RPM, height=1.5, right_axis=right_axis)


@dataclass(frozen=True)
class Display:
    """What the figures show of one kind of part, read by the figures and the tables, never by a run.

    ``panels`` of the run figure, ``shading`` (phases), ``summary_panels`` and ``outcomes`` of the sweep's
    summary figure; ``headline(summary)``: what a run's title says of the part, from the run's summary
    (None: nothing; a KeyError: the run has not the part), which holds the run's ``events`` where the caller
    has them (the run figure: a clutch's story of locks and lets-go; ``watch`` prints the summary alone); ``panels_for(run)``: the panels for a run read
    back (``run["parameters"]`` the resolved scenario) where they are named after parts the user named
    (a drawn drivetrain's), ``panels`` when None; ``reads(column)``: whether the run figure reads a column
    beyond those its ``panels`` name.
    """

    panels: tuple[Panel, ...] = ()
    shading: tuple[Phase, ...] = ()
    summary_panels: tuple[SummaryPanel, ...] = ()
    outcomes: tuple[Outcome, ...] = ()
    headline: Callable[[dict], str | None] | None = None
    panels_for: Callable[[dict], tuple] | None = None
    reads: Callable[[str], bool] | None = None
    # of parts the user named: the phases of a run (read back) and the summary panels and outcomes of a summary
    # row, beside the fixed ``shading``, ``summary_panels`` and ``outcomes``
    shading_for: Callable[[dict], tuple] | None = None
    summary_panels_for: Callable[[dict], tuple] | None = None
    outcomes_for: Callable[[dict], tuple] | None = None
    # a hoist part's display, whose columns its name names: in a drawn drivetrain's run it draws only where the
    # drivetrain has that part, (kind, name) (a clutch the user named "brake" is no brake)
    names_part: tuple[str, str] | None = None

    def shows(self, run: dict) -> bool:
        """Whether it draws in this run (read back: ``run["parameters"]`` the resolved scenario)."""
        drawn = (run.get("parameters") or {}).get("drivetrain")
        if drawn is None or self.names_part is None:
            return True
        kind, name = self.names_part
        return name in (drawn.get(kind) or {})

    def panels_of(self, run: dict) -> tuple:
        if not self.shows(run):
            return ()
        return self.panels if self.panels_for is None else self.panels_for(run)

    def shading_of(self, run: dict) -> tuple:
        if not self.shows(run):
            return ()
        return self.shading + (self.shading_for(run) if self.shading_for else ())

    def summary_panels_of(self, row: dict) -> tuple:
        """Its summary panels for a sweep whose runs' summaries are as ``row`` (under the parts' own names)."""
        return self.summary_panels + (self.summary_panels_for(row) if self.summary_panels_for else ())

    def outcomes_of(self, row: dict) -> tuple:
        return self.outcomes + (self.outcomes_for(row) if self.outcomes_for else ())

    def reads_column(self, column: str) -> bool:
        return self.reads is not None and self.reads(column)

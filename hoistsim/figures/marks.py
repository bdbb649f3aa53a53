"""The dots on a run's curves: observed instants (a lock, a lift-off, a peak) and a curve's lowest point.

Each dot lies wholly inside its panel: a dot at the first or last instant (a load still falling at the end of
the run is lowest there) would be cut in half by the panel's edge, so the time axis is widened by a dot's
radius where one lies that close to an end.
"""

from __future__ import annotations

import numpy as np

from .base import row_text

NAMES = {"lock": "clutch locks", "lift_off": "lift-off", "touch_down": "touch-down", "rope_force_peak": "peak"}
SHAPES = {"lift_off": "^", "touch_down": "v", "rope_force_peak": "D"}  # else a circle
LIMIT_COLOUR = "#b2182b"
EDGE = 0.012  # of the time axis: a dot nearer an end than this widens the axis by as much (a dot is ~0.6 %)


def draw_marks(ax, trace, scale, runs, run_colours, mode) -> list[float]:
    """Draw ``trace``'s dots of each run; returns their times (to keep them off the panel's edges)."""
    times = []
    for kind in trace.marks:
        xs, ys, cs = [], [], []
        for run, colour in zip(runs, run_colours):
            values = trace.of(run)
            found = [float(row["time"]) for row in run["events"] if row_text(row, "kind") == kind
                     and (trace.marks_of is None or row_text(row, "element") == trace.marks_of)]
            if values is None or not found:
                continue
            xs += found
            ys += list(np.interp(found, run["time"], values * scale))
            cs += ["k" if colour is None else colour] * len(found)
        if xs:
            _dots(ax, xs, ys, cs, NAMES.get(kind, kind.replace("_", " ")), SHAPES.get(kind, "o"), mode,
                  warning=kind in limits_crossed(runs))
            times += xs
    if trace.lowest is not None:
        xs, ys, cs = [], [], []
        for run, colour in zip(runs, run_colours):
            values = trace.of(run)
            if values is None or not np.nanmin(values) < 0.0:
                continue  # never below zero: its lowest point is where it started
            at = int(np.nanargmin(values))  # the exact turning instants are rows of the run
            xs.append(float(run["time"][at]))
            ys.append(float(values[at] * scale))
            cs.append("k" if colour is None else colour)
        if xs:
            _dots(ax, xs, ys, cs, trace.lowest, "o", mode)
            times += xs
    return times


def _dots(ax, xs, ys, colours, name, shape, mode, warning=False):
    if warning:  # a limit crossed: a warning, in red
        ax.scatter(xs, ys, s=40 if mode != "family" else 14, c=LIMIT_COLOUR, marker="v", lw=0, zorder=4, label=name)
    elif mode == "family":
        ax.scatter(xs, ys, s=6, c="k", marker=shape, lw=0, zorder=3, label=name)
    else:
        ax.scatter(xs, ys, s=28, facecolors="white", edgecolors=colours, marker=shape, lw=1.3, zorder=3, label=name)


def time_limits(start: float, end: float, marked) -> tuple[float, float]:
    """The time axis from ``start`` to ``end``, widened at an end that a dot at one of ``marked`` would touch."""
    span = (end - start) or 1.0
    low = start - EDGE * span if any(t - start < EDGE * span for t in marked) else start
    high = end + EDGE * span if any(end - t < EDGE * span for t in marked) else end
    return low, high


def limits_crossed(runs) -> set:
    """The kinds of limit the runs crossed (a temperature limit): their instants are warnings."""
    return {row_text(row, "kind") for run in runs for row in run["events"] if row_text(row, "category") == "limit"}

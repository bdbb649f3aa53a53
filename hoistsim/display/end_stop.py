"""A mass's hard stops: the push of each end on its mass, and the kinetic energy its impacts took."""

from __future__ import annotations

import numpy as np

from .panel import Display, Panel, Trace, drawn_parts

ENDS = ("lower", "upper")


def _panels_for(run: dict) -> tuple:
    # the ends that ever pushed (an end met only in impacts, the mass leaving it at once, is in the title)
    ends = [(name, end, stops["mass"]) for name, stops in drawn_parts(run, "stops").items() for end in ENDS
            if stops.get(end) is not None and np.any(np.asarray(run.get(f"{name}_{end}_force", 0.0)) != 0.0)]
    if not ends:
        return ()
    traces = tuple(Trace(f"{name} {end} on {mass}", f"{name}_{end}_force", marks=("stop_reached", "stop_rebound"),
                         marks_of=f"{name}_{end}") for name, end, mass in ends)
    return (Panel("stop_forces", "stop force [N]\n(push on the mass)", 3, traces, zero_line=True, height=0.8),)


def _impacts(summary: dict) -> list[tuple[str, str, float]]:
    """(stops, its end, the kinetic energy its impacts took) for each end whose impacts took any."""
    return [(*key.removesuffix("_impact_loss").rsplit("_", 1), float(value)) for key, value in summary.items()
            if key.endswith(tuple(f"_{end}_impact_loss" for end in ENDS)) and float(value) > 0.0]


def _headline(summary: dict) -> str | None:
    said = [f"impacts on {name}'s {end} stop take {lost:.3g} J" for name, end, lost in _impacts(summary)]
    return "; ".join(said) or None


END_STOP = Display(panels_for=_panels_for, headline=_headline,
                   reads=lambda column: column.endswith(("_lower_force", "_upper_force")))

"""A vehicle's driving resistances: each force on its mass."""

from __future__ import annotations

from .panel import Display, Panel, Trace, drawn_parts

RESISTANCES = ("rolling", "drag", "grade")


def _panels_for(run: dict) -> tuple:
    traces = tuple(Trace(f"{name} {what}", f"{name}_{what}_force") for name in drawn_parts(run, "vehicles")
                   for what in RESISTANCES if f"{name}_{what}_force" in run)
    return (Panel("driving_resistances", "driving resistance [N]\n(on the vehicle)", 6, traces, zero_line=True,
                  height=0.8),) if traces else ()


VEHICLE = Display(panels_for=_panels_for,
                  reads=lambda column: column.endswith(tuple(f"_{what}_force" for what in RESISTANCES)))

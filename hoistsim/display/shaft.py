"""A drawn drivetrain's shafts: every shaft's speed in one panel, named as the user named them."""

from __future__ import annotations

from .panel import Display, Panel, Trace, drawn_parts


def _panels_for(run: dict) -> tuple:
    shafts = drawn_parts(run, "shafts")
    traces = tuple(Trace(name, f"{name}_speed") for name in shafts)
    return (Panel("shaft_speeds", "shaft speed [rad/s]", 0, traces, height=1.5),) if traces else ()


SHAFT = Display(panels_for=_panels_for, reads=lambda column: column.endswith("_speed"))

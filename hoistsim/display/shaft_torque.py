"""A drawn drivetrain's external torques on shafts (of time or of speed): one panel, each named by its place."""

from __future__ import annotations

from .panel import Display, Panel, Trace, drawn_parts


def _panels_for(run: dict) -> tuple:
    torques = drawn_parts(run, "torques")
    traces = tuple(Trace(f"torque{i + 1} on {entry['shaft']}", f"torque{i + 1}") for i, entry in enumerate(torques))
    return (Panel("shaft_torques", "external torque [N*m]", 5, traces, zero_line=True, height=0.8),) if traces else ()


SHAFT_TORQUE = Display(panels_for=_panels_for, reads=lambda column: column.startswith("torque"))

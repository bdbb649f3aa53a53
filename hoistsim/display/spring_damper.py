"""A drawn drivetrain's springs and dampers: the torque each passes, one panel, named as the user named them."""

from __future__ import annotations

from .panel import Display, Panel, Trace


def _panels_for(run: dict) -> tuple:
    springs = (run.get("parameters", {}).get("drivetrain") or {}).get("springs") or {}
    traces = tuple(Trace(name, f"{name}_torque") for name in springs)
    return (Panel("spring_torques", "spring and damper\ntorque [N*m]", 15, traces, zero_line=True),) if traces else ()


SPRING_DAMPER = Display(panels_for=_panels_for, reads=lambda column: column.endswith("_torque"))

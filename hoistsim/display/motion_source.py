"""A drawn drivetrain's motion sources: the torque each takes to hold its shaft to the motion it prescribes."""

from __future__ import annotations

from .panel import Display, Panel, Trace


def _sources(run: dict) -> dict:
    return (run.get("parameters", {}).get("drivetrain") or {}).get("motion_sources") or {}


def _panels_for(run: dict) -> tuple:
    traces = tuple(Trace(f"{name} on {spec['shaft']}", f"{name}_torque") for name, spec in _sources(run).items())
    return (Panel("motion_sources", "motion source's\ntorque [N*m]", 4, traces, zero_line=True, height=0.8),
            ) if traces else ()


MOTION_SOURCE = Display(panels_for=_panels_for, reads=lambda column: column.endswith("_torque"))

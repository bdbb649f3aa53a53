"""A drawn drivetrain's motion sources: the torque each takes to hold its shaft to the motion it prescribes."""

from __future__ import annotations

from .panel import Display, Panel, Trace, drawn_parts, on_line


def _panels_for(run: dict) -> tuple:
    panels = []
    for word, units, line in (("torque", "N*m", False), ("force", "N", True)):
        traces = tuple(Trace(f"{name} on {spec['shaft']}", f"{name}_{word}")
                       for name, spec in drawn_parts(run, "motion_sources").items()
                       if on_line(run, spec["shaft"]) == line)
        if traces:
            panels.append(Panel(f"motion_source_{word}s", f"motion source's\n{word} [{units}]", 4, traces,
                                zero_line=True, height=0.8))
    return tuple(panels)


MOTION_SOURCE = Display(panels_for=_panels_for, reads=lambda column: column.endswith(("_torque", "_force")))

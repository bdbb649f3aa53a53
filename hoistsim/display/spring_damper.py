"""A drawn drivetrain's springs and dampers: the torque each passes, one panel, named as the user named them."""

from __future__ import annotations

from .panel import Display, Panel, Trace, drawn_parts, on_line


def _panels_for(run: dict) -> tuple:
    panels = []
    for word, units, line in (("torque", "N*m", False), ("force", "N", True)):  # between shafts, on a line
        traces = tuple(Trace(name, f"{name}_{word}") for name, spec in drawn_parts(run, "springs").items()
                       if on_line(run, *spec["between"]) == line)
        if traces:
            panels.append(Panel(f"spring_{word}s", f"spring and damper\n{word} [{units}]", 15, traces,
                                zero_line=True))
    return tuple(panels)


SPRING_DAMPER = Display(panels_for=_panels_for, reads=lambda column: column.endswith(("_torque", "_force")))

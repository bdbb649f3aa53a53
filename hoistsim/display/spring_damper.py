"""A drawn drivetrain's springs and dampers: the torque each passes, one panel, named as the user named them."""

from __future__ import annotations

from .panel import Display, Panel, Trace


def _panels_for(run: dict) -> tuple:
    drawn = run.get("parameters", {}).get("drivetrain") or {}
    springs, masses = drawn.get("springs") or {}, drawn.get("masses") or {}
    panels = []
    for word, units, on_line in (("torque", "N*m", False), ("force", "N", True)):  # between shafts, on a line
        traces = tuple(Trace(name, f"{name}_{word}") for name, spec in springs.items()
                       if any(side in masses for side in spec["between"]) == on_line)
        if traces:
            panels.append(Panel(f"spring_{word}s", f"spring and damper\n{word} [{units}]", 15, traces,
                                zero_line=True))
    return tuple(panels)


SPRING_DAMPER = Display(panels_for=_panels_for, reads=lambda column: column.endswith(("_torque", "_force")))

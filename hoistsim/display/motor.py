"""The hoist's motor: its shaft's speed on top."""

from __future__ import annotations

from .panel import Display, Trace, speed_panel

PANELS = (speed_panel(Trace("motor", "motor_speed")),)


def _panels_for(run: dict) -> tuple:
    # a drawn drivetrain's shaft may be named motor: its speed is in the shafts' panel, not the hoist's
    return () if (run.get("parameters") or {}).get("drivetrain") else PANELS


MOTOR = Display(panels=PANELS, panels_for=_panels_for)

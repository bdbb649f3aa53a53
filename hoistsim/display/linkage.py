"""A drawn drivetrain's linkages of three shafts (planetary sets, stages on a turning housing): the torques
with which their shafts drive them, a panel each."""

from __future__ import annotations

from .panel import Display, Panel, Trace


def _panels_for(run: dict) -> tuple:
    drawn = run.get("parameters", {}).get("drivetrain") or {}
    sets = [(name, ("sun", "carrier", "ring")) for name in drawn.get("planetaries") or {}]
    housed = [(name, ("input", "output", "housing")) for name, stage in (drawn.get("gears") or {}).items()
              if stage.get("housing") is not None]
    return tuple(Panel(f"{name}_torques", f"{name}\ntorques [N*m]", 25 + i,
                       tuple(Trace(word, f"{name}_{word}_torque") for word in words), zero_line=True, height=0.8)
                 for i, (name, words) in enumerate(sets + housed))


LINKAGE = Display(panels_for=_panels_for, reads=lambda column: column.endswith("_torque"))

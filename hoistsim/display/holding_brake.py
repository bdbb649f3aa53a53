"""The holding brake: the torque it holds at the drum, the phase it holds."""

from __future__ import annotations

import numpy as np

from .panel import Display, Panel, Phase, Trace, drawn_parts


def _brake_panel(label: str, where: str = "at the drum") -> Panel:
    return Panel("brake", f"brake torque [N*m]\n({where})", 40, (Trace(label, "brake_torque"),), zero_line=True,
                 height=0.8)


PANELS = (_brake_panel("holding the load up"),)


def _panels_for(run: dict) -> tuple:
    # a brake that holds a load lifted against it (a motor starting against a slipping brake) holds it down:
    # its legend says which sign is which, not "holding the load up" over a negative torque; a drawn brake is
    # on the shaft the user put it on (the hoist's is on the drum)
    drawn = drawn_parts(run, "brakes")
    where = f"on shaft {drawn['brake']['shaft']}" if "brake" in drawn else "at the drum"
    torque = run.get("brake_torque")
    if torque is not None and (np.asarray(torque) < 0).any():
        return (_brake_panel("brake torque\n(+ holds the load up)", where),)
    return PANELS if where == "at the drum" else (_brake_panel("holding the load up", where),)


HOLDING_BRAKE = Display(
    panels=PANELS,
    shading=(Phase("brake holding", "brake_engaged", 1, "#8c510a", hatch="///"),),
    names_part=("brakes", "brake"),
    panels_for=_panels_for,
)

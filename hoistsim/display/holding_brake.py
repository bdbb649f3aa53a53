"""The holding brake: the torque it holds at the drum, the phase it holds."""

from __future__ import annotations

from .panel import Display, Panel, Phase, Trace

HOLDING_BRAKE = Display(
    panels=(Panel("brake", "brake torque [N*m]\n(at the drum)", 40, (Trace("holding the load up", "brake_torque"),),
                  zero_line=True, height=0.8),),
    shading=(Phase("brake holding", "brake_engaged", 1, "#8c510a", hatch="///"),),
    names_part=("brakes", "brake"),
)

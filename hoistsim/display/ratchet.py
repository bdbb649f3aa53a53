"""The ratchet: the torque its pawl holds at the drum, the phase it holds."""

from __future__ import annotations

from .panel import Display, Panel, Phase, Trace

RATCHET = Display(
    panels=(Panel("ratchet", "pawl torque [N*m]\n(at the drum)", 41, (Trace("holding the load up", "ratchet_torque"),),
                  zero_line=True, height=0.8),),
    shading=(Phase("pawl holding", "ratchet_engaged", 1, "#5e3c99", hatch="\\\\\\"),),
    names_part=("ratchets", "ratchet"),
)

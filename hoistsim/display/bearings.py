"""The drum shaft's loads: its bearings' reactions, the tooth force and the rope's tension."""

from __future__ import annotations

from .panel import Display, Panel, Trace

DRUM_SHAFT_LOADS = Display(panels=(Panel("drum_shaft_loads", "drum-shaft loads [kN]", 50, (
    Trace("bearing A", "bearing_A"), Trace("bearing B", "bearing_B", style="--"),
    Trace("tooth force", "tooth_force", style="-."), Trace("rope tension", "rope_tension", style=":"),
), scale=1e-3, height=1.1),))

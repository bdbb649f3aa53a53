"""The hoist's gear pair: the drum's speed as a second scale of the clutch output's."""

from __future__ import annotations

from .panel import Display, speed_panel

# The clutch output turns with the pinion, z2/z1 times as fast as the drum: the drum's speed is a second
# scale of the same curve.
GEAR_PAIR = Display(panels=(speed_panel(right_axis=(
    "drum speed [rpm]\n(clutch output / gear ratio)",
    lambda parameters: parameters["gears"]["pinion_teeth"] / parameters["gears"]["wheel_teeth"])),))

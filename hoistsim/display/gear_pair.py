"""The hoist's gear pair: its pinion's speed (the clutch output's) on the speed panel, the drum's as a second
scale of it."""

from __future__ import annotations

from .panel import Display, Trace, speed_panel

# The hoist's file keeps no pinion speed: the pinion turns with the clutch output, the motor's speed less the
# clutch's slip.  It turns z2/z1 times as fast as the drum: the drum's speed is a second scale of the same curve.
GEAR_PAIR = Display(panels=(speed_panel(
    Trace("clutch output (pinion)", "pinion_speed", style="--", needs=("motor_speed", "slip_speed"),
          value=lambda run: run["motor_speed"] - run["slip_speed"]),
    right_axis=("drum speed [rpm]\n(clutch output / gear ratio)",
                lambda parameters: parameters["gears"]["pinion_teeth"] / parameters["gears"]["wheel_teeth"])),))

"""A hoist started lifting at its steady speed (``initial.steady_lift``): its starting speeds set where the
motor's torque holds the load.

The linear motor's C(omega) = C0 (1 - omega/omega0) against the load's weight brought to the motor shaft,
M g R / tau (the parts' own formulas, as the two-shaft model reduces them).  Worked out where the scenario is
lowered (:mod:`.lowering`): the parts the hoist's template writes out start at these speeds.
"""

from __future__ import annotations

from ..components import Drum, GearPair, HangingLoad
from ..errors import ScenarioError


def steady_lift_speed(scenario) -> float:
    """rad/s: the motor's speed at which its torque equals the load torque (the hoist lifting at constant
    speed)."""
    if scenario.motor.characteristic != "linear":
        raise ScenarioError("initial.steady_lift", "needs a linear motor (stall_torque + no_load_speed)")
    motor, gears = scenario.motor, scenario.gears
    ratio = GearPair(gears.pinion_teeth, gears.wheel_teeth, gears.module, gears.pressure_angle).ratio
    rope_radius = Drum(scenario.drum.diameter, scenario.drum.inertia).rope_radius
    load_torque = HangingLoad(scenario.load.mass, scenario.gravity).weight * rope_radius / ratio
    return motor.no_load_speed * (1.0 - load_torque / motor.stall_torque)


def with_steady_lift(scenario):
    """With ``initial.steady_lift``, the scenario with its initial speeds set to the steady lifting speed."""
    if not scenario.initial.steady_lift:
        return scenario
    speed = steady_lift_speed(scenario)
    ratio = scenario.gears.wheel_teeth / scenario.gears.pinion_teeth
    return scenario.model_copy(update={"initial": scenario.initial.model_copy(
        update={"motor_speed": speed, "drum_speed": speed / ratio})})

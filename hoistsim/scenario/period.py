"""The machine's period: when every periodic part is back where it started.

A torque periodic in the motor angle (period Theta_m) and one periodic in the
drum angle (Theta_r, brought to the motor shaft through the gear's exact
fraction of teeth) repeat together only after Theta = k_m Theta_m = k_r Theta_r
with k_m, k_r coprime integers.  Periods are read as exact fractions of a turn
(whole numbers of 1e-4 deg), so the multiple is exact.
"""

from __future__ import annotations

import math
from fractions import Fraction

from ..errors import ScenarioError

TURN = 2 * math.pi
# Periods are read as whole numbers of this fraction of a degree (a period off every one is refused).
STEPS_PER_DEGREE = 10_000


def turns(angle: float, key: str) -> Fraction:
    """An angle (rad) as an exact fraction of a turn: a whole number of 1e-4 deg."""
    steps = math.degrees(angle) * STEPS_PER_DEGREE
    if abs(steps - round(steps)) > 1e-5:  # round-off of a period given in deg is far smaller
        raise ScenarioError(key, f"{math.degrees(angle):.12g} deg is not a whole number of 1e-4 deg; the "
                            "machine's period needs periods that are exact fractions of a turn (give them in deg)")
    return Fraction(round(steps), 360 * STEPS_PER_DEGREE)


def common_multiple(a: Fraction, b: Fraction) -> Fraction:
    """The least common multiple of two positive fractions: lcm of numerators over gcd of denominators."""
    return Fraction(math.lcm(a.numerator, b.numerator), math.gcd(a.denominator, b.denominator))


def periods_on_motor(scenario) -> dict[str, Fraction]:
    """Each periodic part's period in turns of the motor shaft, by its scenario key."""
    out = {}
    if scenario.motor.ripple is not None:
        out["motor.ripple.period"] = turns(scenario.motor.ripple.period, "motor.ripple.period")
    if scenario.drum.resisting_ripple is not None:
        # the drum turns pinion/wheel times as fast as the motor (clutch locked)
        gear = Fraction(scenario.gears.wheel_teeth, scenario.gears.pinion_teeth)
        drum = turns(scenario.drum.resisting_ripple.period, "drum.resisting_ripple.period")
        out["drum.resisting_ripple.period"] = drum * gear
    if scenario.reciprocating is not None:
        out["reciprocating"] = Fraction(1)  # the slider-crank repeats every turn of its crank
    return out


def machine_period_turns(scenario) -> Fraction:
    """The machine's period in turns of the motor shaft (one turn when nothing in it is periodic)."""
    period = None
    for value in periods_on_motor(scenario).values():
        period = value if period is None else common_multiple(period, value)
    return period if period is not None else Fraction(1)


def machine_period(scenario) -> float:
    """The machine's period in rad of motor angle."""
    return float(machine_period_turns(scenario)) * TURN

"""Derivatives through the switches of each element against central differences of hoistsim's own runs.

For a scene of each element that switches (the rope's lift-off, the brake's stop, the ratchet, the two-speed
shift, CoupledClutches' three clutches), the difference quotient over a step h shrinking tenfold converges on
the derivative as h squared, until round-off: its error at the smallest step is within 1e-6 of the derivative.
"""

from __future__ import annotations

import pytest
from helpers import SCENARIOS

from hoistsim import load_scenario, simulate
from hoistsim.running.sensitivity import sensitivity

CASES = {
    "rope lift-off": ("lift_off_the_ground.yaml", [], "load.mass", ["lift_off_time", "peak_rope_force"]),
    "brake stop": ("brake_stop_on_an_elastic_rope.yaml", [], "brake.kinetic_torque",
                   ["brake_energy", "peak_rope_force"]),
    "ratchet": ("clutch_duty_cycle.yaml", ["simulation.duration=6 s"], "load.mass",
                ["slip_energy", "final_load_position"]),
    "two-speed shift": ("two_speed_hoist.yaml", [], "drivetrain.clutches.high_clutch.kinetic_friction",
                        ["high_clutch_lockup_time", "high_clutch_slip_energy"]),
    "CoupledClutches": ("coupled_clutches.yaml", [], "drivetrain.clutches.clutch1.kinetic_friction",
                        ["clutch1_lockup_time", "clutch2_lockup_time", "clutch3_lockup_time"]),
}
STEPS = (1e-3, 1e-4, 1e-5)  # relative to the key's value


@pytest.mark.slow
@pytest.mark.parametrize("name", CASES)
def test_the_derivative_is_where_differences_of_the_runs_converge(name):
    file, overrides, key, names = CASES[name]
    path = SCENARIOS / file
    result = sensitivity(load_scenario(path, overrides=overrides), [key], of=names)
    x = result.keys[key]
    errors = {summary: [] for summary in names}
    for step in STEPS:
        h = step * abs(x)
        up, down = (simulate(load_scenario(path, overrides=overrides + [f"{key}={x + d!r}"])).values
                    for d in (h, -h))
        for summary in names:
            errors[summary].append(abs((up[summary] - down[summary]) / (2 * h) - result.derivatives[summary][key]))
    for summary in names:
        size = abs(result.derivatives[summary][key])
        assert size > 0, summary  # a derivative that is zero would check nothing
        first, second, third = errors[summary]
        # as h squared, or at round-off already (an instant located to ~1e-12 s, over a step of ~1e-4)
        assert second < first / 30 or second < 1e-6 * size, (summary, errors[summary])
        assert third < 1e-6 * size, (summary, errors[summary], size)

"""Hard cases stay numerically stable: a named suite of scenes in tests/hard/, each with its expectation.

Every scene (files run at rtol 1e-10) must give finite outputs, the closed
form's switches at its times, its speeds, a closed energy balance and the same
bits on a second run.  The expectation of each file is written in its header
and repeated here, so a change of the closed form cannot silently move it.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import TESTS, scene, reduced

from hoistsim import exact_from_scenario, load_scenario, simulate

# Slow: every hard case is a structure of its own, compiled for its fixture.
pytestmark = pytest.mark.slow

HARD = TESTS / "hard"

EXPECTED = {  # file -> the switches it must show (and the closed form must agree)
    "stiff_motor.yaml": ["lock"],
    "huge_drum.yaml": ["lock"],
    "load_at_static_limit.yaml": [],
    "load_just_under_limit.yaml": [],
    "equal_friction.yaml": ["lock", "unlock", "lock"],
    "zero_kinetic_friction.yaml": ["unlock", "disengage"],
    "zero_force.yaml": [],
    "force_step_at_lock.yaml": ["lock"],
    "oscillating_force.yaml": ["unlock", "lock"] * 12,
    "reverse_slip.yaml": ["lock"],
    "motor_above_no_load.yaml": ["lock"],
    "brake_released_at_start.yaml": ["brake_release", "lock"],
    "brake_released_at_end.yaml": ["engage"],
    "ten_minutes.yaml": ["lock"],
}


def test_every_file_has_an_expectation():
    assert sorted(p.name for p in HARD.glob("*.yaml")) == sorted(EXPECTED)


@pytest.fixture(scope="module", params=sorted(EXPECTED))
def case(request):
    s = load_scenario(HARD / request.param)
    return request.param, s, simulate(s), exact_from_scenario(s)


def test_outputs_are_finite(case):
    _, _, run, _ = case
    for name, values in run.series.items():
        assert np.all(np.isfinite(values)), name


def test_switches_match_the_expectation_and_the_exact_solution(case):
    name, _, run, exact = case
    assert [e.kind for e in exact.events] == EXPECTED[name]
    assert list(run.events["kind"]) == EXPECTED[name]
    np.testing.assert_allclose(run.events["time"], [e.time for e in exact.events], rtol=0, atol=1e-8)


def test_speeds_match_the_exact_solution(case):
    _, _, run, exact = case
    ref = exact.evaluate(run.time)
    assert np.max(np.abs(run["motor_speed"] - ref["motor_speed"])) < 1e-6
    assert np.max(np.abs(run["drum_speed"] * reduced(run).ratio - ref["output_speed"])) < 1e-6


def test_energy_balance_closes(case):
    _, _, run, _ = case
    assert run.energy_balance["relative_residual"] < 1e-8


def test_two_runs_give_identical_bits(case):
    _, s, run, _ = case
    again = simulate(s)
    assert np.array_equal(run.time, again.time)
    for name, values in run.series.items():
        assert np.array_equal(values, again.series[name]), name


def test_force_step_sits_exactly_on_the_lock_instant():
    stepped = load_scenario(HARD / "force_step_at_lock.yaml")
    step = stepped.clutch.engagement_force.times[1]
    plain = scene(force="6000 N", motor_speed="300 rpm", duration="2 s")
    assert exact_from_scenario(plain).events[0].time == pytest.approx(step, abs=1e-12)


def test_static_limit_holds_and_just_over_breaks_away():
    at_limit = simulate(load_scenario(HARD / "load_at_static_limit.yaml"))
    assert np.all(at_limit["clutch_locked"] == 1) and np.ptp(at_limit["motor_speed"]) < 1e-12
    over = load_scenario(HARD / "load_at_static_limit.yaml", overrides={"load.mass": "843.63 kg"})  # +0.1 %
    run = simulate(over)
    assert run["clutch_locked"][0] == 0 and run["load_position"][-1] < 0


@pytest.mark.parametrize("file", ["equal_friction.yaml", "oscillating_force.yaml"])
def test_every_tolerance_from_1e3_to_1e12_keeps_the_switches(file):
    base = load_scenario(HARD / file)
    exact = exact_from_scenario(base)
    errors = []
    for rtol in [10.0**-k for k in range(3, 13)]:
        s = load_scenario(HARD / file, overrides={"simulation.rtol": rtol, "simulation.atol": rtol * 1e-2})
        run = simulate(s)
        assert list(run.events["kind"]) == EXPECTED[file], rtol
        ref = exact.evaluate(run.time)
        errors.append(np.max(np.abs(run["motor_speed"] - ref["motor_speed"])))
        if rtol <= 1e-8:
            assert run.energy_balance["relative_residual"] < 1e-6, rtol
    assert errors[-1] < 1e-8 and errors[-1] < errors[0] * 1e-5  # accuracy follows the tolerance

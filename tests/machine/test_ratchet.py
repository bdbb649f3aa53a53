"""The ratchet (pawl) on the drum shaft against independent answers.

A pawl that holds the load matches the holding brake released at the same
instant; a load thrown up and left to itself is caught exactly where the drum
stops, at the time the reduced machine's uniform deceleration gives.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest
from helpers import EXERCISE6, SCENARIOS, TIGHT

from hoistsim import scenario_from_dict, scenario_from_text, simulate
from hoistsim.errors import ScenarioError
from hoistsim.references.model import Machine


def _runback(extra: str):
    text = (SCENARIOS / "runback_slipping_clutch.yaml").read_text()
    return scenario_from_text(text + extra, overrides=TIGHT)


def _events(run, element):
    mine = run.events["element"] == element
    return list(zip(run.events["kind"][mine], run.events["time"][mine]))


def test_the_run_back_scene_with_a_ratchet_holds_its_load():
    run = simulate(_runback("ratchet: {}\n"))
    assert np.abs(run["load_position"]).max() < 1e-20 and np.abs(run["drum_speed"]).max() < 1e-20  # round-off
    assert run["ratchet_engaged"].all()
    load_torque = 500 * 9.81 * 0.2  # M g R at the drum: the pawl carries it, less what the clutch passes
    assert 0 < run["ratchet_torque"][-1] < load_torque
    assert run.summary["energy_relative_residual"] < 1e-8


@pytest.mark.slow  # a structure of its own to compile
def test_a_ratchet_released_is_the_holding_brake_released_at_the_same_time():
    pawl = simulate(_runback("ratchet:\n  release_time: 0.4 s\n"))
    brake = simulate(_runback("brake:\n  release_time: 0.4 s\n"))
    for name in ("motor_speed", "drum_speed", "load_position", "slip_speed", "clutch_energy"):
        np.testing.assert_allclose(pawl[name], brake[name], rtol=0, atol=1e-12 * (1 + np.abs(brake[name]).max()),
                                   err_msg=name)
    np.testing.assert_allclose(pawl["ratchet_torque"], brake["brake_torque"], rtol=1e-12, atol=1e-9)
    assert ("ratchet_release", 0.4) in _events(pawl, "ratchet")


@pytest.mark.slow  # a structure of its own to compile
def test_a_load_thrown_up_is_caught_where_the_drum_stops():
    """Clutch pressed at 3201 N for 1 s, then opened: the drum slows at T_L / J_b (pinion-shaft terms)
    and the pawl catches it where its speed falls through zero; it holds from then on."""
    data = copy.deepcopy(EXERCISE6)
    data["clutch"]["engagement_force"] = [["0 s", "3201 N"], ["1 s", "3201 N"], ["1 s", "0 N"]]
    data["ratchet"] = {}
    data["simulation"].update(duration="2 s", rtol=1e-10, atol=1e-12)
    scenario = scenario_from_dict(data)
    run = simulate(scenario)
    d = Machine.from_scenario(scenario).reduced()
    tau = scenario.gears.wheel_teeth / scenario.gears.pinion_teeth
    at_one = np.interp(1.0, run.time, run["drum_speed"])
    stop = 1.0 + at_one * tau * d.output_inertia / d.load_torque
    locks = [t for kind, t in _events(run, "ratchet") if kind == "lock"]
    assert locks[-1] == pytest.approx(stop, rel=1e-9)
    assert abs(run["drum_speed"][-1]) < 1e-12 and run["ratchet_engaged"][-1] == 1
    top = np.interp(locks[-1], run.time, run["load_position"])
    assert run["load_position"][-1] == pytest.approx(top, rel=1e-12)  # held at the top, not run back
    assert run.summary["energy_relative_residual"] < 1e-8


def test_a_pawl_on_a_lowering_drum_is_refused():
    text = (SCENARIOS / "runback_slipping_clutch.yaml").read_text()
    with pytest.raises(ScenarioError, match="initial.drum_speed: must not be negative with a ratchet"):
        scenario_from_text(text + "ratchet: {}\n", overrides=["initial.drum_speed=-1 rad/s"])


def test_a_pawl_beside_a_brake_leaves_the_brake_the_load_until_it_lets_go():
    # Both hold the drum while the brake is on: the torque is statically indeterminate, and the brake,
    # first in the machine's order, carries it all; once released, the pawl takes the load at once.
    run = simulate(_runback("ratchet: {}\nbrake:\n  release_time: 1 s\n"))
    on = run.time < 1.0
    assert np.abs(run["ratchet_torque"][on]).max() == 0.0 and run["brake_torque"][on].min() > 0
    assert run["ratchet_torque"][~on].min() > 0 and run["ratchet_engaged"][~on].all()
    assert np.abs(run["drum_speed"]).max() < 1e-20
    # what the drum needs held is the same whoever holds it
    assert run["ratchet_torque"][-1] == pytest.approx(run["brake_torque"][on][-1], rel=1e-12)
    assert run.summary["energy_relative_residual"] < 1e-8

"""The friction brake on the drum shaft against independent answers.

A load lowered at a known speed and caught by the brake's kinetic torque
decelerates uniformly until it stops: its stopping time, the brake's heat and
the height lost are closed forms of the reduced machine (Machine.reduced(),
the two-shaft model the closed-form solution of the clutch uses).
"""

from __future__ import annotations

import copy

import numpy as np
import pytest
from helpers import SCENARIOS, TIGHT

from hoistsim import load_scenario, scenario_from_dict, scenario_from_text, simulate
from hoistsim.references.model import Machine


def _caught(kinetic="1200 N*m", static="1500 N*m", speed="-2.5 rad/s", duration="4 s"):
    """The lowering scene with the brake closed from the start (released only after the run)."""
    text = (SCENARIOS / "lowering_on_the_brake.yaml").read_text()
    closed = text.replace("  release_time: 0 s\n  apply_time: 0.5 s\n", "  release_time: 10 s\n")
    assert closed != text
    return scenario_from_text(closed, overrides=TIGHT + [
        f"brake.kinetic_torque={kinetic}", f"brake.static_torque={static}", f"initial.drum_speed={speed}",
        f"simulation.duration={duration}"])


def _closed_form(scenario):
    """Stopping time, brake heat and height lost of a drum at -w0 slowed by T_k - M g R (pinion-shaft terms)."""
    d = Machine.from_scenario(scenario).reduced()
    tau = scenario.gears.wheel_teeth / scenario.gears.pinion_teeth
    kinetic = scenario.brake.kinetic_torque / tau  # at the pinion shaft, where J_b and T_L are
    speed = -scenario.initial.drum_speed * tau
    stop = speed * d.output_inertia / (kinetic - d.load_torque)
    heat = kinetic * speed * stop / 2
    drop = 0.5 * scenario.drum.diameter * (speed / tau) * stop / 2
    return stop, heat, drop


def test_a_falling_load_caught_by_the_brake_stops_as_the_closed_form_says():
    scenario = _caught()
    run = simulate(scenario)
    stop, heat, drop = _closed_form(scenario)
    locks = run.events["time"][(run.events["kind"] == "lock") & (run.events["element"] == "brake")]
    assert len(locks) == 1
    assert locks[0] == pytest.approx(stop, rel=1e-9)
    assert run.summary["brake_energy"] == pytest.approx(heat, rel=1e-9)
    assert run.summary["final_load_position"] == pytest.approx(-drop, rel=1e-9)
    assert abs(run["drum_speed"][-1]) < 1e-12  # held: 981 N*m of load against 1500 N*m static
    assert run.summary["energy_relative_residual"] < 1e-8
    slipping = run.time < stop
    np.testing.assert_allclose(run["brake_torque"][slipping], 1200.0, rtol=1e-12)
    assert run["brake_heat"][-1] == pytest.approx(heat, rel=1e-9)


def test_a_brake_too_weak_for_the_load_lets_it_run_down():
    """Kinetic torque below the load's (981 N*m): the load gains speed at (M g R - T_k) / J, never stops."""
    scenario = _caught(kinetic="800 N*m", static="900 N*m", duration="1 s")
    run = simulate(scenario)
    assert not ((run.events["kind"] == "lock") & (run.events["element"] == "brake")).any()
    d = Machine.from_scenario(scenario).reduced()
    tau = scenario.gears.wheel_teeth / scenario.gears.pinion_teeth
    rate = (800.0 / tau - d.load_torque) / d.output_inertia / tau  # drum acceleration, rad/s^2
    assert run["drum_speed"][-1] == pytest.approx(-2.5 + rate * 1.0, rel=1e-9)
    assert run.summary["energy_relative_residual"] < 1e-8


@pytest.mark.slow  # a structure of its own to compile
def test_a_held_drum_lets_go_when_the_brake_is_released_and_is_caught_when_applied():
    """The shipped scene: released at 0 s, applied at 0.5 s; lowering, then held. Events name the brake."""
    run = simulate(load_scenario(SCENARIOS / "lowering_on_the_brake.yaml", overrides=TIGHT))
    kinds = list(zip(run.events["kind"], run.events["element"]))
    assert ("brake_apply", "brake") in kinds and ("lock", "brake") in kinds
    assert run.summary["brake_energy"] > 0 and run.summary["energy_relative_residual"] < 1e-8
    assert set(run.series) >= {"brake_torque", "brake_engaged", "brake_mode", "brake_heat", "brake_capacity"}


def test_a_holding_brake_scene_has_no_friction_brake_columns():
    from helpers import EXERCISE6

    data = copy.deepcopy(EXERCISE6)
    data["brake"] = {"release_time": "0.5 s"}
    data["simulation"]["duration"] = "1 s"
    run = simulate(scenario_from_dict(data))
    assert "brake_torque" in run.series and "brake_heat" not in run.series and "brake_energy" not in run.summary


@pytest.mark.slow  # a structure of its own to compile
def test_a_start_where_the_brake_slips_before_it_lets_go():
    """Clutch drive above load + static torque: the brake unlocks before its release and slips at its
    kinetic torque; its heat is that torque times the drum's turn while it slipped (the load's rise / R)."""
    scenario = load_scenario(SCENARIOS / "start_against_a_slipping_brake.yaml", overrides=TIGHT)
    run = simulate(scenario)
    unlock = run.events["time"][(run.events["kind"] == "unlock") & (run.events["element"] == "brake")]
    assert len(unlock) == 1 and 0.5 < unlock[0] < scenario.brake.release_time
    rope = 0.5 * scenario.drum.diameter
    rise = np.interp([unlock[0], scenario.brake.release_time], run.time, run["load_position"])
    heat = scenario.brake.kinetic_torque * (rise[1] - rise[0]) / rope
    assert run.summary["brake_energy"] == pytest.approx(heat, rel=1e-8)
    slipping = (run.time > unlock[0]) & (run.time < scenario.brake.release_time)
    np.testing.assert_allclose(run["brake_torque"][slipping], -scenario.brake.kinetic_torque, rtol=1e-12)
    assert run.summary["energy_relative_residual"] < 1e-8


@pytest.mark.slow  # two structures of their own to compile
def test_the_brake_applied_exactly_at_the_clutch_lock():
    """A hard case: the brake closes on the turning drum at the very instant the clutch locks (the lock
    time of the same start without the apply, as a float): one boundary and one root at one time.
    The run goes on without chattering, the brake slips from there, and the ledger closes."""
    text = (SCENARIOS / "engage_at_speed_with_brake.yaml").read_text()
    friction = text.replace("brake:\n  release_time: 0.6 s\n",
                            "brake:\n  release_time: 0.6 s\n  static_torque: 3000 N*m\n  kinetic_torque: 1500 N*m\n")
    assert friction != text
    free = simulate(scenario_from_text(friction, overrides=TIGHT))
    lock = float(free.events["time"][(free.events["kind"] == "lock") & (free.events["element"] == "clutch")][0])
    run = simulate(scenario_from_text(friction, overrides=TIGHT + [f"brake.apply_time={lock!r} s"]))
    kinds = list(zip(run.events["kind"], run.events["element"]))
    assert ("brake_apply", "brake") in kinds
    apply = run.events["time"][run.events["kind"] == "brake_apply"][0]
    assert apply == lock
    after = run.time > lock
    assert (run["brake_mode"][after][:10] == 1).all()  # slipping as the load rises
    np.testing.assert_allclose(run["brake_torque"][after][:10], -1500.0, rtol=1e-12)
    assert run.summary["brake_energy"] > 0 and run.summary["energy_relative_residual"] < 1e-8

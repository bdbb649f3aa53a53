"""The lossy gear mesh against independent answers.

A mesh that drives forward throughout is the ideal machine with the load torque
and the drum-side inertia divided by the efficiency; one that the load drives
back throughout is the ideal machine with them multiplied by the backdrive
efficiency: the closed form of the canonical scene, either way.  Its losses are
(1/eta - 1) times the energy the drum side has gained, or (1 - eta_b) times what
it has given.  Efficiency 1 is the ideal mesh; a mesh whose backdrive losses
exceed what the load can overhaul holds the load at rest.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers import SCENARIOS, TIGHT

from hoistsim import scenario_from_text, simulate
from hoistsim.references.exact import solve_exact
from hoistsim.references.model import ForceSchedule, Machine, initial_speeds


def _scene(name: str, *overrides: str):
    return scenario_from_text((SCENARIOS / name).read_text(), overrides=[*TIGHT, *overrides])


def _ideal_with_drum_side_scaled(scenario, factor: float):
    """The closed form of the ideal machine whose drum side (inertia and load torque) is multiplied by factor."""
    machine = Machine.from_scenario(scenario)
    d = machine.reduced()
    pinion_side = machine.driven_inertia + machine.gears.pinion_inertia
    scaled = dataclasses.replace(d, output_inertia=pinion_side + (d.output_inertia - pinion_side) * factor,
                                 load_torque=d.load_torque * factor)
    schedule = ForceSchedule.from_scenario(scenario)
    motor_speed, output_speed = initial_speeds(scenario, d)
    brake = getattr(scenario, "brake", None)
    return d, scaled, solve_exact(scaled, schedule.times, schedule.forces, scenario.simulation.duration,
                                  initial_motor_speed=motor_speed, initial_output_speed=output_speed,
                                  brake_release=brake.release_time if brake else None)


def _drum_side_energy(scenario, run):
    """Kinetic energy of the drum side (wheel, drum, load) and the load's potential energy (J)."""
    machine = Machine.from_scenario(scenario)
    d = machine.reduced()
    pinion_side = machine.driven_inertia + machine.gears.pinion_inertia
    drum_side = (d.output_inertia - pinion_side) * d.ratio**2  # at the drum shaft
    return 0.5 * drum_side * run["drum_speed"] ** 2 + d.load_weight * run["load_position"]


def test_a_mesh_that_drives_forward_throughout_is_the_ideal_machine_with_its_drum_side_divided_by_eta():
    eta = 0.9
    scenario = _scene("engage_at_speed_with_brake.yaml", f"gears.efficiency={eta}", "gears.backdrive_efficiency=0.6")
    run = simulate(scenario)
    d, _, exact = _ideal_with_drum_side_scaled(scenario, 1.0 / eta)
    closed = exact.evaluate(run.time)
    scale = d.no_load_speed
    assert np.abs(run["motor_speed"] - closed["motor_speed"]).max() < 1e-8 * scale
    assert np.abs(run["drum_speed"] * d.ratio - closed["output_speed"]).max() < 1e-8 * scale
    assert np.abs(run["load_position"] - closed["load_position"]).max() < 1e-8 * closed["load_position"].max()
    locks = run.events["time"][(run.events["kind"] == "lock") & (run.events["element"] == "clutch")]
    exact_locks = [e.time for e in exact.events if e.kind == "lock"]
    assert locks == pytest.approx(exact_locks, abs=1e-8)
    moving = run.time >= scenario.brake.release_time  # the row at the release holds the state after it
    assert (run["mesh_mode"][moving] == 1).all() and (run["mesh_mode"][~moving] == 0).all()
    # the losses: (1/eta - 1) of what the drum side gained
    gained = _drum_side_energy(scenario, run)
    assert run["mesh_heat"] == pytest.approx((1.0 / eta - 1.0) * gained, rel=1e-8, abs=1e-6)
    assert run.summary["energy_relative_residual"] < 1e-8


@pytest.mark.slow
def test_a_mesh_the_load_drives_back_throughout_is_the_ideal_machine_with_its_drum_side_times_eta_b():
    eta_b = 0.8
    scenario = _scene("runback_slipping_clutch.yaml", "gears.efficiency=0.95", f"gears.backdrive_efficiency={eta_b}")
    run = simulate(scenario)
    d, _, exact = _ideal_with_drum_side_scaled(scenario, eta_b)
    closed = exact.evaluate(run.time)
    assert np.abs(run["motor_speed"] - closed["motor_speed"]).max() < 1e-8 * d.no_load_speed
    assert np.abs(run["drum_speed"] * d.ratio - closed["output_speed"]).max() < 1e-8 * d.no_load_speed
    going = run.time > 0
    assert (run["drum_speed"][going] < 0).all() and (run["mesh_mode"][going] == 2).all()
    given = -_drum_side_energy(scenario, run)
    assert run["mesh_heat"] == pytest.approx((1.0 - eta_b) * given, rel=1e-8, abs=1e-6)
    assert run.summary["energy_relative_residual"] < 1e-8


def test_efficiency_one_is_the_ideal_mesh():
    ideal = simulate(_scene("engage_at_speed_with_brake.yaml"))
    lossless = simulate(_scene("engage_at_speed_with_brake.yaml", "gears.efficiency=1"))
    for column in ("motor_speed", "drum_speed", "load_position", "clutch_torque"):
        assert np.abs(lossless[column] - ideal[column]).max() <= 1e-9 * np.abs(ideal[column]).max()
    assert np.abs(lossless["mesh_heat"]).max() == 0.0
    assert "mesh_loss_energy" not in ideal.summary and "mesh_torque" not in ideal.series


def test_a_mesh_that_loses_more_than_the_load_can_overhaul_holds_it_at_rest():
    # The slipping clutch passes 104 N*m to the pinion; the load pulls back 185 N*m there, 92.6 N*m of it
    # through a mesh that gives back half: the gear stays still, and forward the pinion passes 94 N*m of
    # the 185 it would need.  Self-locking: the load neither runs back nor rises.
    run = simulate(_scene("runback_slipping_clutch.yaml", "gears.efficiency=0.9", "gears.backdrive_efficiency=0.5"))
    assert np.abs(run["drum_speed"]).max() == 0.0 and np.abs(run["load_position"]).max() < 1e-20  # round-off
    assert (run["mesh_mode"] == 0).all() and run.summary["mesh_loss_energy"] == 0.0
    assert run["motor_speed"][-1] > 20.0  # the motor runs up, the clutch slipping all along
    assert run.summary["energy_relative_residual"] < 1e-8


def _coasting(*overrides: str, motor_torque: str = "0 N*m"):
    """The drum thrown up at 30 rpm, the motor heavy (and off): the clutch brakes the pinion until it locks."""
    text = (SCENARIOS / "runback_slipping_clutch.yaml").read_text()
    text = text.replace("  stall_torque: 500 N*m\n  no_load_speed: 300 rpm\n", f"  torque: {motor_torque}\n")
    text = text.replace("rotor_mass: 40 kg", "rotor_mass: 400 kg")
    return scenario_from_text(text, overrides=[*TIGHT, "gears.efficiency=0.9", "gears.backdrive_efficiency=0.8",
                                               "gears.pinion_inertia=0.5 kg*m^2", "initial.drum_speed=30 rpm",
                                               *overrides])


@pytest.mark.slow
def test_the_power_flow_reverses_at_the_instant_the_clutch_locks():
    # Before the lock the clutch brakes the pinion harder than the load brakes the drum: the wheel drives
    # (the drum side times eta_b); locked, the motor's inertia carries the drum up: the pinion drives
    # (the drum side over eta).  Each phase is uniformly decelerated: lock and stop in closed form.
    eta, eta_b = 0.9, 0.8
    scenario = _coasting("clutch.engagement_force=3000 N")
    run = simulate(scenario)
    machine = Machine.from_scenario(scenario.model_copy(update={"motor": scenario.motor.model_copy(
        update={"torque": None, "stall_torque": 1.0, "no_load_speed": 1.0})}))
    d = machine.reduced()
    pinion_side = machine.driven_inertia + machine.gears.pinion_inertia
    drum_side = d.output_inertia - pinion_side
    kinetic = d.kinetic_torque(3000.0)
    w0 = scenario.initial.drum_speed * d.ratio
    motor_accel = kinetic / d.motor_inertia
    pinion_accel = (-kinetic - eta_b * d.load_torque) / (pinion_side + eta_b * drum_side)
    lock = w0 / (motor_accel - pinion_accel)
    together = -(d.load_torque / eta) / (d.motor_inertia + pinion_side + drum_side / eta)
    stop = lock + motor_accel * lock / -together
    events = list(zip(run.events["kind"], run.events["element"], run.events["time"]))
    assert [(k, e) for k, e, _ in events] == [("lock", "clutch"), ("reversal", "mesh")]
    assert events[0][2] == pytest.approx(lock, abs=1e-9) and events[1][2] == pytest.approx(stop, abs=1e-9)
    at = np.flatnonzero(run.time == events[0][2])[0]
    assert run["mesh_torque"][at - 1] < 0 < run["mesh_torque"][at]
    assert run["mesh_mode"][at - 1] == 2 and run["mesh_mode"][at] == 1
    assert run.summary["energy_relative_residual"] < 1e-8


@pytest.mark.slow
def test_a_tooth_load_changing_sign_while_the_gear_rolls_is_found_exactly():
    # The motor drives downwards while the drum, thrown up, stops and runs back, and the clutch force ramps
    # up: the clutch drives the pinion down ever harder, the tooth load falls through zero with the gear
    # turning, and the law of the losses changes there: a row of its own at the zero, not a step across it.
    # (With the motor off there is no such zero: the clutch, dragged along, reverses as the pinion passes
    # the motor's speed, 6 ms before the drum stops, and brakes the running back from then on.)
    run = simulate(_coasting("clutch.engagement_force=[[0 s, 0 N], [1 s, 3000 N]]", motor_torque="-400 N*m"))
    found = run.instants["time"][run.instants["kind"] == "power_reversal"]
    assert len(found) == 1 and run.instants["element"][run.instants["kind"] == "power_reversal"][0] == "mesh"
    at = np.flatnonzero(run.time == found[0])[0]
    assert abs(run["mesh_torque"][at]) < 1e-9 * np.abs(run["mesh_torque"]).max()
    assert run["drum_speed"][at] < 0 and run["mesh_mode"][at - 1] == 2 and run["mesh_mode"][at] == 1
    assert run.summary["energy_relative_residual"] < 1e-8


def test_two_switches_in_one_step_are_both_found_in_order():
    # The motor off and dragged along by the slipping clutch: the clutch's slip passes zero (the pinion
    # slowing past the motor) 6 ms before the drum stops and the mesh reverses, in the same step.  Both are
    # switches; the earlier is found first, and the clutch never slips against its own mode.
    run = simulate(_coasting("clutch.engagement_force=[[0 s, 0 N], [1 s, 3000 N]]"))
    switches = [(e, k) for e, k in zip(run.events["element"], run.events["kind"])]
    assert switches[:2] == [("clutch", "reversal"), ("mesh", "reversal")]
    assert run.events["time"][0] < run.events["time"][1] < run.events["time"][0] + 0.01
    slip, mode = run["slip_speed"], run["clutch_mode"]
    assert (slip[mode == 1] >= -1e-9).all() and (slip[mode == 2] <= 1e-9).all()


@pytest.mark.slow
def test_the_shipped_scene_lifts_with_the_pinion_driving_and_runs_back_with_the_wheel_driving():
    run = simulate(_scene("lift_and_run_back_through_a_lossy_mesh.yaml"))
    turn = run.events["time"][(run.events["element"] == "mesh") & (run.events["kind"] == "reversal")]
    assert len(turn) == 1 and 2.0 < turn[0] < 2.5
    lifting = (run.time > 0.6) & (run.time < turn[0])
    assert (run["mesh_mode"][lifting] == 1).all() and (run["mesh_mode"][run.time > turn[0]] == 2).all()
    assert run["load_position"][-1] < 0 and run.summary["mesh_loss_energy"] > 0
    assert run.summary["energy_relative_residual"] < 1e-8


@pytest.mark.slow
def test_a_drum_stopped_by_the_brake_locks_brake_pawl_and_mesh_at_one_instant():
    # Every friction element at once: the friction brake applied again at 2.5 s catches the rising drum
    # against the clutch; where the drum stops the brake, the pawl and the gear held at rest all lock at
    # the same instant (one zero of the drum's speed), the brake taking the load (first in order).
    text = (SCENARIOS / "engage_at_speed_with_brake.yaml").read_text() + "ratchet: {}\n"
    run = simulate(scenario_from_text(text, overrides=[*TIGHT, "brake.static_torque=3000 N*m",
                                                      "brake.kinetic_torque=2000 N*m", "brake.apply_time=2.5 s",
                                                      "gears.efficiency=0.95", "gears.backdrive_efficiency=0.9"]))
    locks = {e: t for k, e, t in zip(run.events["kind"], run.events["element"], run.events["time"])
             if k == "lock" and t > 2.5}
    assert set(locks) == {"mesh", "brake", "ratchet"} and len(set(locks.values())) == 1
    held = run.time >= locks["brake"]
    assert np.abs(run["drum_speed"][held]).max() == 0.0 and (run["mesh_mode"][held] == 0).all()
    assert np.abs(run["brake_torque"][held]).min() > 0 and np.abs(run["ratchet_torque"][held]).max() == 0.0
    assert run.summary["energy_relative_residual"] < 1e-8


def test_the_closed_form_and_the_scipy_peer_refuse_a_lossy_mesh():
    from hoistsim.references.exact import exact_from_scenario
    from hoistsim.references.scipy_reference import solve_scenario_with_scipy

    scenario = _scene("engage_at_speed_with_brake.yaml", "gears.efficiency=0.9")
    for solve in (exact_from_scenario, solve_scenario_with_scipy):
        with pytest.raises(ValueError, match="ideal mesh only"):
            solve(scenario)

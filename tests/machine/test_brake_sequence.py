"""A hoist drive's brake sequence (a speed controller's brake_sequence working a brake operated_by it), against
closed forms: an emergency stop's time and distance with a constant brake torque after the brake's closing
time, on a rigid rope; the rollback with the drive's torque at zero from the brake's release, a constant
acceleration.  The sequence's instants (release after the proof and the opening time, apply after the command
and the closing time), the ledger, and bad input (one line naming the key).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import SCENARIOS, refused_in_one_line
from ruamel.yaml import YAML

from hoistsim import load_scenario, scenario_from_dict, simulate

ESTOP, SEQUENCE = SCENARIOS / "emergency_stop_lowering.yaml", SCENARIOS / "inverter_hoist_brake_sequence.yaml"
MASS, RADIUS, RATIO, G = 1000.0, 0.2, 30.0, 9.81
INERTIA = 0.25 + (20.0 + MASS * RADIUS ** 2) / RATIO ** 2  # kg*m^2 at the motor: the motor, the drum, the load
LOAD = MASS * G * RADIUS / RATIO  # N*m at the motor, pulling it backwards (lowering)


def _data(path) -> dict:
    return YAML(typ="safe").load(path.read_text(encoding="utf-8"))


def test_an_emergency_stop_on_a_rigid_rope_is_two_constant_accelerations():
    """Lowering at the motor's speed w0 when the drive is switched off: it falls freely for the brake's closing
    time d (w' = -T_L / J), then the brake's kinetic torque T_k stops it (w' = (T_k - T_L) / J): stopped after
    d + w1 / a2, the rope paid out R / i (|w0| d + |a1| d^2 / 2 + w1^2 / (2 a2))."""
    data = _data(ESTOP)
    del data["drivetrain"]["load"]["rope"]  # a rigid rope
    run = simulate(scenario_from_dict(data))
    w0 = run["motor_speed"][np.searchsorted(run.time, 2.5, side="right") - 1]  # the state at the e-stop's row
    d, a1, a2 = 0.2, LOAD / INERTIA, (130.0 - LOAD) / INERTIA  # sizes: speeding up, then slowing down
    w1 = abs(w0) + a1 * d
    assert run.summary["stopping_time"] == pytest.approx(d + w1 / a2, rel=1e-8)
    distance = RADIUS / RATIO * (abs(w0) * d + 0.5 * a1 * d * d + w1 * w1 / (2 * a2))
    assert run.summary["stopping_distance"] == pytest.approx(distance, rel=1e-7)  # a state, to rtol 1e-9 a step
    assert run.summary["drive_release_time"] == pytest.approx(0.3, abs=1e-12)  # proven at once: the opening time
    kinds = list(run.instants["kind"])
    assert run.instants["time"][kinds.index("brake_apply")] == pytest.approx(2.7, abs=1e-10)
    assert run.summary["energy_relative_residual"] < 1e-9


def test_an_overspeed_trip_stops_the_load_from_the_trip_speed():
    """The drive asked for 1700 rpm lowering, its trip at 1600 rpm: where the motor's speed first passes it (a
    located crossing, the row ``drive_overspeed``) the drive is switched off, and the stop is the two constant
    accelerations' of the emergency stop from w0 = 1600 rpm exactly; the drive gives nothing from then on."""
    data = _data(ESTOP)
    del data["drivetrain"]["load"]["rope"]  # a rigid rope
    drive = data["drivetrain"]["speed_controllers"]["drive"]
    del drive["emergency_stop_at"]
    drive.update({"emergency_stop_above": "1600 rpm", "reference": [["0 s", "0 rpm"], ["0.6 s", "0 rpm"],
                                                                    ["1.6 s", "-1700 rpm"]]})
    run = simulate(scenario_from_dict(data))
    kinds = list(run.instants["kind"])
    trip = kinds.index("drive_overspeed")
    tripped = run.instants["time"][trip]
    assert run["motor_speed"][run.instant_rows()[trip]] == pytest.approx(-1600 * math.pi / 30, rel=1e-10)
    w0, d, a1, a2 = 1600 * math.pi / 30, 0.2, LOAD / INERTIA, (130.0 - LOAD) / INERTIA
    w1 = w0 + a1 * d
    assert run.summary["stopping_time"] == pytest.approx(d + w1 / a2, rel=1e-8)
    distance = RADIUS / RATIO * (w0 * d + 0.5 * a1 * d * d + w1 * w1 / (2 * a2))
    assert run.summary["stopping_distance"] == pytest.approx(distance, rel=1e-7)
    assert np.all(run["drive_torque"][run.time > tripped] == 0.0)
    assert run.instants["time"][kinds.index("brake_apply")] == pytest.approx(tripped + d, abs=1e-9)  # the root's
    assert run.summary["energy_relative_residual"] < 1e-9


def test_the_rollback_with_no_drive_torque_is_a_constant_acceleration():
    """A drive that can give no torque (1 uN*m) and proves none: the brake opens after its opening time and the
    load runs back at w' = -T_L / J: the rope paid out to the end of the run is R / i a (t - t_r)^2 / 2."""
    data = _data(SEQUENCE)
    drive = data["drivetrain"]["speed_controllers"]["drive"]
    drive.update({"max_torque": "1e-6 N*m", "output": "0 N*m", "reference": [["0 s", "0 rpm"], ["1 s", "0 rpm"]]})
    drive["brake_sequence"].update({"prove_torque": "0 N*m", "stop_at": "0.9 s"})
    data["simulation"]["duration"] = "0.8 s"
    run = simulate(scenario_from_dict(data))
    fallen = RADIUS / RATIO * 0.5 * (LOAD / INERTIA) * (0.8 - 0.3) ** 2
    assert run.summary["rollback_distance"] == pytest.approx(fallen, rel=1e-6)
    assert run.summary["drive_proven_torque"] == pytest.approx(0.0, abs=1e-6)


@pytest.fixture(scope="module")
def sequence():
    return simulate(load_scenario(SEQUENCE))


def test_the_brake_opens_after_the_proof_and_closes_after_the_stop(sequence):
    """Proven at once (its 50 N*m pre-torque above the 45 N*m it proves): released at the opening time, 0.3 s;
    the stop command at 4 s finds the motor below 10 rpm: applied at 4.2 s; the drive then lets go of the load
    and the brake holds it."""
    run = sequence
    kinds, times = list(run.instants["kind"]), run.instants["time"]
    assert times[kinds.index("brake_release")] == pytest.approx(0.3, abs=1e-12)
    assert times[kinds.index("drive_stop")] == 4.0
    assert times[kinds.index("brake_apply")] == pytest.approx(4.2, abs=1e-10)
    held = run.time > 4.25
    assert np.all(run["brake_engaged"][held] == 1) and np.all(run["brake_engaged"][(run.time > 0.31)
                                                                                 & (run.time < 4.19)] == 0)
    # the brake applied, the drive takes its torque away (through its 5 ms current loop): the brake holds the load
    late = run.time > 4.4
    assert np.max(np.abs(run["drive_torque"][late])) < 1e-9 * LOAD
    np.testing.assert_allclose(run["brake_torque"][late], LOAD, rtol=1e-9)
    assert run.summary["drive_proven_torque"] == pytest.approx(50.0, rel=1e-12)
    # the load ran back while the drive's 50 N*m fell short of its 65.4 N*m: a millimetre, then lifted
    assert 0.0005 < run.summary["rollback_distance"] < 0.002
    assert run.summary["rollback_distance"] == pytest.approx(-run.summary["lowest_load_position"], rel=1e-6)
    assert run.summary["energy_relative_residual"] < 1e-9


@pytest.mark.parametrize("change, key, says", [
    (lambda d: d["drivetrain"]["speed_controllers"]["drive"]["brake_sequence"].update({"stop_at": "0.2 s"}),
     "drivetrain.speed_controllers.drive.brake_sequence.stop_at", "before it opens"),
    (lambda d: d["drivetrain"]["speed_controllers"]["drive"]["brake_sequence"].update({"brake": "disc"}),
     "drivetrain.speed_controllers.drive.brake_sequence.brake", "no brake 'disc'"),
    (lambda d: d["drivetrain"]["brakes"]["brake"].update({"release_time": "1 s"}),
     "drivetrain.brakes.brake.release_time", "one of the two"),
    (lambda d: d["drivetrain"]["speed_controllers"]["drive"].pop("brake_sequence"),
     "drivetrain.brakes.brake.operated_by", "brake_sequence"),
    (lambda d: d["drivetrain"]["speed_controllers"]["drive"].update({"emergency_stop_at": "3 s"}),
     "drivetrain.speed_controllers.drive.emergency_stop_at", "not both"),
    (lambda d: d["drivetrain"]["speed_controllers"]["drive"].update({"emergency_stop_above": "1600 rpm"})
     or d["drivetrain"]["speed_controllers"]["drive"].pop("brake_sequence"),
     "drivetrain.speed_controllers.drive.emergency_stop_above", "brake_sequence"),
])
def test_bad_input_names_its_key(change, key, says, tmp_path):
    refused_in_one_line(SEQUENCE, change, key, says, tmp_path)


def test_a_drive_switched_off_closes_its_brake_after_its_closing_time():
    """The emergency stop's instant is a scheduled event; from it the drive's torque is nothing."""
    run = simulate(load_scenario(ESTOP))
    after = run.time > 2.5
    assert np.all(run["drive_torque"][after] == 0.0)
    assert math.isfinite(run.summary["stopping_time"]) and run.summary["peak_rope_force"] > MASS * G

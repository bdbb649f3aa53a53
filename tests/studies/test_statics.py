"""Exercise 6's static answers, and the time-domain answers statics cannot give."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SCENARIOS, scene

from hoistsim import load_scenario, simulate
from hoistsim.cli import main
from hoistsim.components import DrumShaft
from hoistsim.references.model import LOCKED, Machine
from hoistsim.studies.statics import as_dict, least_force_for_start

EXERCISE_FILE = SCENARIOS / "exercise6_constant_speed.yaml"
BEARINGS = {"gear_offset": "20 cm", "rope_offset": "40 cm", "span": "80 cm"}

# The exercise's rounded answers (physics.md).  The source rounds the clutch
# capacity to 312 N*m on the way (exact: 312.34), which lowers its P_max, T and
# the reactions by 0.1-0.2 %; F_A is rounded to the newton.
TEXTBOOK = {
    "engagement_force_for_stall_torque": 3201.0,
    "max_load_weight": 8258.0,
    "bearing_A": 14160.0,
    "bearing_B": 4011.0,
}


def test_statics_json_gives_the_exercise_answers():
    result = CliRunner().invoke(main, ["statics", str(EXERCISE_FILE), "--json"])
    assert result.exit_code == 0, result.output
    got = json.loads(result.output)
    for key, book in TEXTBOOK.items():
        assert got[key] == pytest.approx(book, rel=5e-3), key
    assert got["clutch_capacity"] == pytest.approx(312.3, abs=0.05)
    assert got["tooth_radial_force"] == pytest.approx(3340, rel=5e-3)
    for key in ("tooth_tangential_force", "bearing_A", "bearing_B"):
        assert key in got


def test_the_difference_is_the_sources_rounding():
    """With the source's rounded capacity (312 N*m) our formulas give its intermediate numbers."""
    machine = Machine.from_scenario(load_scenario(EXERCISE_FILE))
    tangential = machine.gears.tangential_force(312.0)
    assert tangential == pytest.approx(9176, abs=1)  # T21 = 9176 N in the source
    weight = tangential * machine.gears.wheel_pitch_radius / machine.drum.rope_radius
    assert weight == pytest.approx(8258.4, abs=0.5)  # P = 8258.4 N in the source
    radial = machine.gears.radial_force(tangential)
    r = DrumShaft(0.2, 0.4, 0.8).reactions(tangential, 3340.0, weight)
    assert radial == pytest.approx(3340, abs=1)
    assert r["bearing_B_y"] == pytest.approx(3294, abs=1) and r["bearing_A_y"] == pytest.approx(8304, abs=1)
    assert r["bearing_B_x"] == pytest.approx(-2294, abs=1) and r["bearing_A_x"] == pytest.approx(11470, abs=1)
    assert r["bearing_A"] == pytest.approx(14160, abs=5)


def test_table_output_reads_in_a_terminal():
    result = CliRunner().invoke(main, ["statics", str(EXERCISE_FILE)])
    assert result.exit_code == 0
    assert "P_max" in result.output and "8267.8" in result.output and "R_A" in result.output


def test_least_force_for_a_start_without_slip():
    s = scene(mass="500 kg", duration="1.5 s")
    least = least_force_for_start(s)
    assert least < as_dict(s)["engagement_force_for_stall_torque"]  # the motor's inertia helps
    above = simulate(scene(force=f"{least * (1 + 1e-6)} N", mass="500 kg", duration="1.5 s"))
    assert above.lockup_time == 0.0 and len(above.events["kind"]) == 0
    assert np.all(above["clutch_locked"] == 1)
    below = simulate(scene(force=f"{least * (1 - 1e-6)} N", mass="500 kg", duration="1.5 s"))
    assert below["clutch_locked"][0] == 0 and below["slip_speed"][1] > 0
    # slipping, the clutch passes only a third of its static torque: less than the load's
    assert below["load_position"][-1] < 0 and math.isnan(below.lockup_time)


def _steady_lift(mass_kg):
    """The question-2 scene lifting ``mass_kg`` at the steady locked speed, with bearings."""
    return load_scenario(EXERCISE_FILE, overrides={"load.mass": f"{mass_kg} kg", "simulation.duration": "1 s"})


@pytest.mark.slow
def test_question_2_load_lifted_at_constant_speed_with_static_bearing_loads():
    exercise = as_dict(load_scenario(EXERCISE_FILE))
    mass = exercise["max_load_mass"] * (1 - 1e-9)
    run = simulate(_steady_lift(mass))
    assert np.all(run["clutch_locked"] == 1) and len(run.events["kind"]) == 0
    assert np.ptp(run["motor_speed"]) < 1e-9  # constant speed
    for key in ("bearing_A", "bearing_B", "bearing_A_x", "bearing_B_y", "tooth_tangential_force",
                "tooth_radial_force", "rope_tension"):
        expected = exercise["max_load_weight"] if key == "rope_tension" else exercise[key]
        np.testing.assert_allclose(run[key], expected, rtol=1e-6, err_msg=key)


@pytest.mark.slow
def test_slightly_heavier_load_cannot_be_lifted():
    mass = as_dict(load_scenario(EXERCISE_FILE))["max_load_mass"] * (1 + 1e-3)
    run = simulate(_steady_lift(mass))
    assert run["clutch_locked"][0] == 0  # breaks away at once
    assert math.isnan(run.lockup_time) and run["load_position"][-1] < 0  # and runs back


def test_peak_dynamic_bearing_loads_exceed_the_static_values():
    s = load_scenario(SCENARIOS / "exercise6_direct_start.yaml")
    run = simulate(s)
    d = Machine.from_scenario(s).reduced()
    gears = Machine.from_scenario(s).gears
    # static loads of the same 500 kg lifted at constant speed: the clutch carries T_L
    tangential = gears.tangential_force(d.load_torque)
    static = DrumShaft(0.2, 0.4, 0.8).reactions(tangential, gears.radial_force(tangential), d.load_weight)
    assert run["bearing_A"].max() > 1.5 * static["bearing_A"]
    assert run["rope_tension"].max() > d.load_weight
    # and the dynamic loads settle onto the static ones as the start-up ends
    assert run["bearing_A"][-1] == pytest.approx(static["bearing_A"], rel=1e-3)
    assert run["bearing_B"][-1] == pytest.approx(static["bearing_B"], rel=1e-3)


@pytest.mark.slow
def test_bearing_columns_only_with_the_bearings_section():
    bare = simulate(scene(duration="0.2 s"))
    assert not any(name.startswith(("bearing", "tooth", "rope")) for name in bare.series)
    assert bare["clutch_mode"][0] == LOCKED


def test_statics_warns_of_a_load_the_motor_or_the_clutch_cannot_hold():
    """1400 kg puts 518.8 N*m on the motor shaft, more than C0 = 500 N*m: the least start force is still
    computed (3217.9 N), but a run at 3300 N runs back; the command says so, on stderr."""
    from hoistsim.studies.statics import warnings

    heavy = load_scenario(SCENARIOS / "exercise6_direct_start.yaml", overrides=["load.mass=1400 kg"])
    said = warnings(heavy)
    assert len(said) == 2 and said[0].startswith("load.mass: 1400 kg puts 518.8 N*m")
    assert said[1].startswith("clutch.engagement_force: at 3201 N the clutch holds 499.9 N*m")
    assert warnings(load_scenario(SCENARIOS / "exercise6_direct_start.yaml")) == []
    result = CliRunner().invoke(main, ["statics", str(SCENARIOS / "exercise6_direct_start.yaml"), "--json",
                                       "--set", "load.mass=1400 kg"])
    assert result.exit_code == 0
    assert result.stderr.count("hoistsim: warning: ") == 2
    assert "least_force_for_start" in result.stdout


def _lossy(force="3201 N", efficiency=0.9):
    s = scene(force=force, mass="500 kg", duration="1 s", rtol=1e-10, atol=1e-12)
    return s.model_copy(update={"gears": s.gears.model_copy(update={"efficiency": efficiency})})


@pytest.mark.slow
def test_a_lossy_mesh_in_the_static_answers_and_the_least_start_force():
    # Exercise 6 assumes an ideal mesh: with efficiency eta the heaviest load takes eta, and lifting from
    # rest weighs the drum side 1/eta as much, so the least start force rises; the simulation agrees.
    ideal, lossy = as_dict(scene(mass="500 kg")), as_dict(_lossy())
    assert ideal["mesh_efficiency"] == 1.0 and lossy["mesh_efficiency"] == 0.9
    assert lossy["max_load_weight"] == pytest.approx(0.9 * ideal["max_load_weight"], rel=1e-14)
    least = least_force_for_start(_lossy())
    assert least > ideal["least_force_for_start"]
    above = simulate(_lossy(force=f"{least * (1 + 1e-6)} N"))
    assert len(above.events["kind"]) == 0 and np.all(above["clutch_locked"] == 1)
    assert above["load_position"][-1] > 0 and (above["mesh_mode"][1:] == 1).all()
    below = simulate(_lossy(force=f"{least * (1 - 1e-6)} N"))
    assert below["clutch_locked"][0] == 0

"""A drivetrain drawn as shafts and clutches (``drivetrain:``) against independent answers.

- Modelica's CoupledClutches: the first 0.4 s in closed form (J2 driven by clutch 1's sliding torque
  alone, J1 by the sine torque less it), J1 swinging freely after clutch 1 opens (its speed is the sine
  torque's integral: 2 * 10 / (10 pi) peak to peak), and the FMI cross-check's SystemModeler reference
  (tests/data, where present) to the precision the reference itself has.
- A brake on one shaft: the closed-form stop.  Two shafts through a clutch: the textbook engagement.
- Every run's ledger closes: the torques' work = kinetic energy + every clutch's heat.
- Bad input: one line naming the key, exit 2, nothing written.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SCENARIOS, TESTS

from hoistsim import load_scenario, scenario_from_dict, scenario_from_text, simulate
from hoistsim.cli import main
from hoistsim.errors import ScenarioError

REFERENCE = TESTS / "data" / "coupled_clutches_systemmodeler.csv"
PHASE = 1.57  # rad: clutch 1's force 20 sin(2 pi 0.2 t + 1.57) N, as in the reference


@pytest.fixture(scope="module")
def coupled():
    return simulate(load_scenario(SCENARIOS / "coupled_clutches.yaml"))


def _events(run):
    return [(float(t), str(k), str(e)) for t, k, e in zip(run.events["time"], run.events["kind"],
                                                          run.events["element"])]


@pytest.mark.slow  # three clutches: ~25 s to compile (issue 26's compile time)
def test_coupled_clutches_switch_as_the_modelica_example(coupled):
    got = [(k, e) for _, k, e in _events(coupled)]
    assert got == [("engage", "clutch2"), ("lock", "clutch2"), ("lock", "clutch1"), ("unlock", "clutch1"),
                   ("engage", "clutch3"), ("lock", "clutch1"), ("unlock", "clutch1"), ("lock", "clutch3"),
                   ("disengage", "clutch1")]
    times = [t for t, _, _ in _events(coupled)]
    # clutch 1 opens where its force 20 sin(0.4 pi t + 1.57) falls through zero
    assert times[-1] == pytest.approx((math.pi - PHASE) / (0.4 * math.pi), abs=1e-9)
    assert times[0] == 0.4 and times[4] == 0.9
    assert coupled.summary["energy_relative_residual"] < 1e-9


@pytest.mark.slow  # three clutches: ~25 s to compile (issue 26's compile time)
def test_coupled_clutches_first_phase_in_closed_form(coupled):
    """Until 0.4 s only clutch 1 passes torque, slipping at 0.5 * 20 sin(0.4 pi t + 1.57) N*m."""
    t = coupled.time[coupled.time <= 0.4]
    passed = 10.0 / (0.4 * math.pi) * (math.cos(PHASE) - np.cos(0.4 * math.pi * t + PHASE))
    driven = 10.0 * (1.0 - np.cos(10.0 * math.pi * t)) / (10.0 * math.pi)
    np.testing.assert_allclose(coupled["J2_speed"][: t.size], passed, rtol=0, atol=1e-8)
    np.testing.assert_allclose(coupled["J1_speed"][: t.size], 10.0 + driven - passed, rtol=0, atol=1e-8)
    assert np.all(coupled["J3_speed"][: t.size] == 0.0) and np.all(coupled["J4_speed"][: t.size] == 0.0)


@pytest.mark.slow  # three clutches: ~25 s to compile (issue 26's compile time)
def test_j1_swings_freely_once_clutch1_is_open(coupled):
    opened = (math.pi - PHASE) / (0.4 * math.pi)
    later = coupled.time > opened + 1e-9
    t = coupled.time[later]
    start = np.interp(opened, coupled.time, coupled["J1_speed"])
    expected = start + (math.cos(10 * math.pi * opened) - np.cos(10 * math.pi * t)) / math.pi
    np.testing.assert_allclose(coupled["J1_speed"][later], expected, rtol=0, atol=1e-8)
    swing = coupled["J1_speed"][coupled.time > 1.3]
    assert swing.max() - swing.min() == pytest.approx(2 * 10 / (10 * math.pi), abs=1e-6)
    for shaft in ("J2", "J3", "J4"):  # the rest turn on together, untouched
        assert np.ptp(coupled[f"{shaft}_speed"][later]) < 1e-12


@pytest.mark.slow
@pytest.mark.skipif(not REFERENCE.exists(), reason="the SystemModeler reference is not in tests/data")
def test_coupled_clutches_against_the_systemmodeler_reference(coupled):
    """The reference's own precision ends near 1e-6 rad/s: its J1 is 1.6e-6 off the closed form by 0.1 s
    (the first test's answer, which this run meets to 1e-9), and that error carries on.  So every speed at
    every reference row within 1e-5 rad/s, every switch within 2e-6 s of the reference's event rows."""
    with REFERENCE.open() as f:
        rows = np.asarray([[float(v) for v in row] for row in list(csv.reader(f))[1:]])
    time = rows[:, 0]
    on_grid = np.abs(time * 1000 - np.round(time * 1000)) < 1e-6  # the rows both have (1 ms apart)
    assert on_grid.sum() >= 1501  # every millisecond (a few twice: the event rows at 0.4 s, 0.9 s)
    for k in range(4):
        ours = np.interp(time[on_grid], coupled.time, coupled[f"J{k + 1}_speed"])
        worst = np.max(np.abs(ours - rows[on_grid, k + 1]))
        assert worst < 1e-5, (f"J{k + 1}", worst)
    # the reference marks its events by repeating a row's time; ours must each have one of them nearby
    repeated = np.unique(time[1:][np.diff(time) == 0.0])
    for t, kind, element in _events(coupled):
        assert np.min(np.abs(repeated - t)) < 2e-6, (t, kind, element)


def _drivetrain(shafts, clutches=None, torques=None, duration="1 s"):
    return scenario_from_dict({"name": "drawn", "drivetrain": {"shafts": shafts, "clutches": clutches or {},
                                                               "torques": torques or []},
                               "simulation": {"duration": duration, "output_interval": "10 ms", "rtol": 1e-10,
                                              "atol": 1e-12}}, name="drawn")


def test_a_brake_stops_a_shaft_in_closed_form():
    """A shaft of 2 kg*m^2 at 30 rad/s braked by 0.4 * 500 N * 0.1 m = 20 N*m stops at J w / T = 3 s."""
    scene = _drivetrain({"wheel": {"inertia": "2 kg*m^2", "speed": "30 rad/s"}},
                        {"brake": {"between": ["wheel", "ground"], "static_friction": 0.5, "kinetic_friction": 0.4,
                                   "effective_radius": "0.1 m", "force": "500 N"}}, duration="4 s")
    run = simulate(scene)
    assert _events(run)[0][1:] == ("lock", "brake")
    assert _events(run)[0][0] == pytest.approx(3.0, abs=1e-9)
    rows = run.time <= 3.0
    np.testing.assert_allclose(run["wheel_speed"][rows], 30.0 - 10.0 * run.time[rows], rtol=0, atol=1e-9)
    assert np.all(run["wheel_speed"][run.time > 3.0] == 0.0)
    assert run.summary["brake_slip_energy"] == pytest.approx(0.5 * 2 * 30**2, rel=1e-9)


def test_a_force_ramping_through_zero_opens_the_clutch_where_it_crosses():
    """F = 100 (1 - 2 t) N (a table row at 0 and at 1 s): the clutch slides with 0.1 * F N*m until the force
    crosses zero at 0.5 s, where it opens; each shaft's speed moves by 0.1 * 100 (t - t^2) until then and
    stays.  The crossing is a segment boundary: no step straddles the kink of max(F, 0)."""
    scene = _drivetrain({"a": {"inertia": "1 kg*m^2", "speed": "10 rad/s"}, "b": {"inertia": "1 kg*m^2"}},
                        {"c": {"between": ["a", "b"], "static_friction": 0.2, "kinetic_friction": 0.1,
                               "effective_radius": "1 m", "force": [["0 s", "100 N"], ["1 s", "-100 N"]]}})
    run = simulate(scene)
    t = run.time
    moved = 10.0 * (np.minimum(t, 0.5) - np.minimum(t, 0.5) ** 2)
    np.testing.assert_allclose(run["a_speed"], 10.0 - moved, rtol=0, atol=1e-11)
    np.testing.assert_allclose(run["b_speed"], moved, rtol=0, atol=1e-11)
    assert np.all(run["c_mode"][t > 0.5] == 3) and np.all(run["c_mode"][t < 0.5] == 1)
    assert run.summary["c_slip_energy"] == pytest.approx((10.0**2 - 7.5**2 - 2.5**2) / 2, rel=1e-10)  # kinetic lost


def test_a_brake_holding_a_shaft_at_rest_breaks_away_at_the_first_peak_over_its_capacity():
    """A shaft held at rest by a brake whose capacity falls, 20 - 10 t N*m, against 14 sin(6 pi t) N*m.
    Held, the machine does not move: nothing limits the steps, and a peak of the torque may rise over the
    capacity and fall back within one.  The brake must break away where the torque first reaches its
    capacity (between the peaks at 0.417 s, under it, and 0.75 s, over it), found here independently."""
    from scipy.optimize import brentq

    from hoistsim.machine.core.element import STICK_TOLERANCE, TORQUE_RESOLUTION

    scene = _drivetrain({"wheel": {"inertia": "1 kg*m^2"}},
                        {"brake": {"between": ["wheel", "ground"], "static_friction": 1.0, "kinetic_friction": 0.8,
                                   "effective_radius": "1 m", "force": [["0 s", "20 N"], ["1 s", "10 N"]]}},
                        [{"shaft": "wheel", "torque": {"harmonics": [{"amplitude": "14 N*m", "frequency": "3 Hz"}]}}])
    run = simulate(scene)
    reach = brentq(lambda t: 14 * math.sin(6 * math.pi * t) - ((20 - 10 * t) * (1 + STICK_TOLERANCE) + TORQUE_RESOLUTION),
                   0.6, 0.75, xtol=1e-15)
    assert _events(run)[0][1:] == ("unlock", "brake")
    assert _events(run)[0][0] == pytest.approx(reach, abs=1e-9)
    held = run.time < reach
    assert np.all(run["wheel_speed"][held] == 0.0)


def test_two_shafts_engage_as_the_textbook_says():
    """Ja = 3, Jb = 1 kg*m^2, 40 rad/s apart, T = 0.3 * 200 N * 0.25 m * 2 = 30 N*m: lock-up after
    Ja Jb dw / (T (Ja + Jb)) = 1 s, heat Ja Jb dw^2 / (2 (Ja + Jb)) = 600 J, at the common speed of momentum."""
    scene = _drivetrain({"a": {"inertia": "3 kg*m^2", "speed": "50 rad/s"}, "b": {"inertia": "1 kg*m^2",
                                                                                  "speed": "10 rad/s"}},
                        {"plates": {"between": ["a", "b"], "static_friction": 0.35, "kinetic_friction": 0.3,
                                    "effective_radius": "0.25 m", "surfaces": 2, "force": "200 N"}}, duration="2 s")
    run = simulate(scene)
    assert run.summary["plates_lockup_time"] == pytest.approx(1.0, abs=1e-9)
    assert run.summary["plates_slip_energy"] == pytest.approx(600.0, rel=1e-9)
    assert run["a_speed"][-1] == pytest.approx(40.0, rel=1e-12) and run["b_speed"][-1] == pytest.approx(40.0,
                                                                                                          rel=1e-12)
    assert run.summary["energy_relative_residual"] < 1e-10


BAD = [  # (id, the drivetrain's text, the key, the words)
    ("a clutch joining a shaft to itself",
     "  clutches:\n    c: {between: [a, a], static_friction: 0.3, kinetic_friction: 0.2, effective_radius: 1 m,"
     " force: 10 N}\n", "drivetrain.clutches.c.between", "to itself"),
    ("a clutch to an unknown shaft",
     "  clutches:\n    c: {between: [a, x], static_friction: 0.3, kinetic_friction: 0.2, effective_radius: 1 m,"
     " force: 10 N}\n", "drivetrain.clutches.c.between", "no shaft 'x'"),
    ("ground as the first side",
     "  clutches:\n    c: {between: [ground, a], static_friction: 0.3, kinetic_friction: 0.2, effective_radius: 1 m,"
     " force: 10 N}\n", "drivetrain.clutches.c.between", "no shaft 'ground'"),
    ("a torque on an unknown shaft", "  torques:\n    - {shaft: x, torque: 1 N*m}\n", "drivetrain.torques.0.shaft",
     "no shaft 'x'"),
    ("a force table going back",
     "  clutches:\n    c: {between: [a, b], static_friction: 0.3, kinetic_friction: 0.2, effective_radius: 1 m,"
     " force: [[1 s, 0 N], [0.5 s, 10 N]]}\n", "drivetrain.clutches.c.force", "time goes backwards"),
    ("kinetic above static",
     "  clutches:\n    c: {between: [a, b], static_friction: 0.3, kinetic_friction: 0.4, effective_radius: 1 m,"
     " force: 10 N}\n", "drivetrain.clutches.c.kinetic_friction", "must not exceed"),
    ("a clutch named as a shaft",
     "  clutches:\n    a: {between: [a, b], static_friction: 0.3, kinetic_friction: 0.2, effective_radius: 1 m,"
     " force: 10 N}\n", "drivetrain.clutches.a", "also the name of a shaft"),
    ("an unknown key of a clutch",
     "  clutches:\n    c: {between: [a, b], static_friction: 0.3, kinetic_friction: 0.2, radius: 1 m,"
     " force: 10 N}\n", "drivetrain.clutches.c.radius", "unknown key"),
    ("a clutch with a radius and a cone",
     "  clutches:\n    c: {between: [a, b], static_friction: 0.3, kinetic_friction: 0.2, effective_radius: 1 m,"
     " cone: {inner_radius: 20 cm, outer_radius: 24 cm, half_angle: 25 deg}, force: 10 N}\n",
     "drivetrain.clutches.c.effective_radius", "either effective_radius or cone"),
    ("two gear stages closing a loop with ratios that disagree",
     "  gears:\n    g1: {between: [a, b], ratio: 2}\n    g2: {between: [b, a], ratio: 3}\n",
     "drivetrain.gears.g2.ratio", "gears 'g1' whose ratios disagree"),
    ("a lossy gear stage in a loop of stages",
     "  gears:\n    g1: {between: [a, b], ratio: 2}\n    g2: {between: [b, a], ratio: 0.5, efficiency: 0.9}\n",
     "drivetrain.gears.g2.efficiency", "in a loop of gear stages"),
    ("an efficiency above 1", "  gears:\n    g: {between: [a, b], ratio: 2, efficiency: 1.1}\n",
     "drivetrain.gears.g.efficiency", "1"),
    ("a gear stage on one shaft", "  gears:\n    g: {between: [a, a], ratio: 2}\n", "drivetrain.gears.g.between",
     "to itself"),
    ("a motor on an unknown shaft",
     "  motors:\n    m: {shaft: x, stall_torque: 10 N*m, no_load_speed: 100 rad/s, inertia: 0.1 kg*m^2}\n",
     "drivetrain.motors.m.shaft", "no shaft 'x'"),
]
SHAFTS = "drivetrain:\n  shafts:\n    a: {inertia: 1 kg*m^2, speed: 1 rad/s}\n    b: {inertia: 1 kg*m^2}\n"
SIMULATION = "simulation:\n  duration: 1 s\n  output_interval: 10 ms\n"


@pytest.mark.parametrize("text, key, words", [c[1:] for c in BAD], ids=[c[0] for c in BAD])
def test_a_bad_drivetrain_fails_in_one_line(text, key, words, tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text("name: bad\n" + SHAFTS + text + SIMULATION, encoding="utf-8")
    output = tmp_path / "out.h5"
    result = CliRunner().invoke(main, ["run", str(scenario), "-o", str(output)])
    lines = result.stderr.splitlines()
    assert result.exit_code == 2, result.output
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error: "), lines
    assert f" {key}: " in lines[0] and words in lines[0], lines[0]
    assert "Traceback" not in result.output and not output.exists()


@pytest.mark.parametrize("shafts, key", [
    ("    a: {inertia: 1 kg*m^2}\n    c: {inertia: 0 kg*m^2}\n", "drivetrain.shafts.c.inertia"),
    # geared to a shaft of inertia, or turned by a motor's rotor, a shaft of none is part of a body that has
    ("    a: {inertia: 1 kg*m^2}\n    c: {inertia: 0 kg*m^2}\n  gears:\n    g: {between: [a, c], ratio: 3}\n", None),
    ("    c: {inertia: 0 kg*m^2}\n  motors:\n    m: {shaft: c, torque: 1 N*m, inertia: 0.1 kg*m^2}\n", None),
], ids=["alone", "geared to one", "with a motor"])
def test_a_shaft_without_inertia_needs_something_of_inertia_tied_to_it(shafts, key, tmp_path):
    text = "name: massless\ndrivetrain:\n  shafts:\n" + shafts + SIMULATION
    if key is None:
        assert scenario_from_text(text).drivetrain.shafts["c"].inertia == 0.0
        return
    with pytest.raises(ScenarioError, match=f"{key}: has no inertia and nothing of inertia rigidly tied to it"):
        scenario_from_text(text)


def test_a_drivetrain_with_the_hoists_sections_is_refused(tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text("name: bad\n" + SHAFTS + SIMULATION + "load:\n  mass: 500 kg\n", encoding="utf-8")
    result = CliRunner().invoke(main, ["run", str(scenario), "-o", str(tmp_path / "out.h5")])
    assert result.exit_code == 2 and "load: cannot be given with drivetrain:" in result.stderr

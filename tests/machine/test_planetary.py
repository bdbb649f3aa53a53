"""Linkages of three shafts: a planetary set (Modelica's IdealPlanetary) and a gear stage on a housing that turns
(Modelica's IdealGear with its support used), against closed forms; Modelica's ElasticBearing against Dymola's
published trajectories.

With constant torques a linkage's machine accelerates uniformly: the bodies' equations J_i a_i = tau_i - w_i T
with the relation sum w_i a_i = 0 are a small linear system, solved here with numpy (the set's weights: sun 1,
carrier -(1 + r), ring r; the stage's: input 1, output -r, housing r - 1).  A brake on the ring slips, locks and
breaks away again: with constant torques and a force ramped linearly, its lock and its breakaway come in closed
form too.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import SCENARIOS
from modelica_reference import signals
from test_modelica_examples import deviations

from hoistsim import load_scenario, scenario_from_dict, simulate
from hoistsim.errors import ScenarioError

J_SUN, J_CARRIER, J_RING = 0.2, 1.5, 0.8
R = 3.0  # the ring's teeth over the sun's: 90 / 30
TAU = 5.0  # N*m on the sun
SUN_SPEED, RING_SPEED = 10.0, 2.0  # rad/s at the start; the carrier's (4 rad/s) is derived
MU_STATIC, MU_KINETIC, RADIUS = 0.3, 0.25, 0.1  # the ring's brake
APPLIED, HOLDING_UNTIL, RELEASED = 0.5, 1.0, 2.0  # s: the brake's force steps to F at 0.5 s, falls from 1 s to 0 at 2 s
FORCE = 400.0  # N
TOL = {"rtol": 1e-10, "atol": 1e-12}


def planetary_scene(force: float = FORCE, **planetary) -> dict:
    """The set with an inertia on each shaft, a torque on the sun, a brake on the ring (force 0: never applied)."""
    brake_force = [["0 s", "0 N"], [f"{APPLIED} s", "0 N"], [f"{APPLIED} s", f"{force} N"],
                   [f"{HOLDING_UNTIL} s", f"{force} N"], [f"{RELEASED} s", "0 N"]]
    return {"name": "planetary", "drivetrain": {
        "shafts": {"sun": {"inertia": f"{J_SUN} kg*m^2", "speed": f"{SUN_SPEED} rad/s", "angle": "0 rad"},
                   "carrier": {"inertia": f"{J_CARRIER} kg*m^2", "angle": "0 rad"},
                   "ring": {"inertia": f"{J_RING} kg*m^2", "speed": f"{RING_SPEED} rad/s", "angle": "0 rad"}},
        "torques": [{"shaft": "sun", "torque": f"{TAU} N*m"}],
        "planetaries": {"set": {"sun": "sun", "carrier": "carrier", "ring": "ring", "teeth": [30, 90], **planetary}},
        "clutches": {"brake": {"between": ["ring", "ground"], "static_friction": MU_STATIC,
                               "kinetic_friction": MU_KINETIC, "effective_radius": f"{RADIUS} m",
                               "force": brake_force}}},
        "simulation": {"duration": "2.5 s", "output_interval": "5 ms", **TOL}}


def uniform(inertias, weights, torques, held=()):
    """Accelerations and the linkage's torque T of J a = tau - w T (less a held shaft's reaction), sum w a = 0,
    the ``held`` shafts' accelerations zero: numpy's solve of the whole linear system."""
    n = len(inertias)
    rows = [[*(inertias[i] if j == i else 0.0 for j in range(n)), weights[i], *(1.0 if h == i else 0.0 for h in held)]
            for i in range(n)]
    rows.append([*weights, 0.0, *(0.0 for _ in held)])
    rows += [[*(1.0 if j == h else 0.0 for j in range(n)), 0.0, *(0.0 for _ in held)] for h in held]
    solved = np.linalg.solve(np.asarray(rows), np.asarray([*torques, 0.0, *(0.0 for _ in held)]))
    return solved[:n], solved[n]


WEIGHTS = (1.0, -(1.0 + R), R)  # sun, carrier, ring
INERTIAS = (J_SUN, J_CARRIER, J_RING)


def willis(run):
    return (1 + R) * run["carrier_speed"] - run["sun_speed"] - R * run["ring_speed"]


def test_a_planetary_set_turns_by_willis_and_balances_its_torques_in_closed_form():
    """No brake: uniform accelerations of the 2-DOF system; Willis's relation to round-off along the run; the
    torques 1 : r : -(1 + r) (static balance), their power zero; the carrier's speed derived from Willis."""
    run = simulate(scenario_from_dict(planetary_scene(force=0.0)))
    accel, torque = uniform(INERTIAS, WEIGHTS, (TAU, 0.0, 0.0))
    t = run["time"]
    carrier_start = (SUN_SPEED + R * RING_SPEED) / (1 + R)
    for shaft, a, start in zip(("sun", "carrier", "ring"), accel, (SUN_SPEED, carrier_start, RING_SPEED)):
        np.testing.assert_allclose(run[f"{shaft}_speed"], start + a * t, rtol=0, atol=1e-10, err_msg=shaft)
        np.testing.assert_allclose(run[f"{shaft}_angle"], start * t + a * t**2 / 2, rtol=0, atol=1e-10, err_msg=shaft)
    assert np.max(np.abs(willis(run))) < 1e-13 * np.max(np.abs(run["sun_speed"]))
    sun, carrier, ring = (run[f"set_{m}_torque"] for m in ("sun", "carrier", "ring"))
    np.testing.assert_allclose(sun, torque, rtol=1e-12)
    np.testing.assert_allclose(ring, R * sun, rtol=1e-14)
    np.testing.assert_allclose(carrier, -(1 + R) * sun, rtol=1e-14)
    power = sun * run["sun_speed"] + carrier * run["carrier_speed"] + ring * run["ring_speed"]
    assert np.max(np.abs(power)) < 1e-12 * np.max(np.abs(sun * run["sun_speed"]))
    assert len(run.events["time"]) == 0  # a set has no switch; an open brake none either
    assert run.summary["energy_relative_residual"] < 1e-9


def test_a_brake_on_the_ring_slips_locks_and_breaks_away_in_closed_form():
    """The brake steps to F at 0.5 s: the ring slips against F mu_k r_e and locks where its speed reaches zero;
    held, it carries r T_held; the force falls from 1 s: it breaks away where F(t) mu_s r_e = r T_held, and
    slips backwards.  Each switch found by the root-finding, at the closed form's instant."""
    run = simulate(scenario_from_dict(planetary_scene()))
    free, _ = uniform(INERTIAS, WEIGHTS, (TAU, 0.0, 0.0))
    ring_applied = RING_SPEED + free[2] * APPLIED
    assert ring_applied > 0.0
    braked, _ = uniform(INERTIAS, WEIGHTS, (TAU, 0.0, -MU_KINETIC * RADIUS * FORCE))
    lock = APPLIED - ring_applied / braked[2]
    _, held_torque = uniform(INERTIAS, WEIGHTS, (TAU, 0.0, 0.0), held=(2,))
    ring_holding = R * held_torque  # what the ring drives the set with, held
    breakaway = HOLDING_UNTIL + (FORCE - ring_holding / (MU_STATIC * RADIUS)) / FORCE * (RELEASED - HOLDING_UNTIL)
    events = [(float(t), str(k)) for t, k, e in zip(run.events["time"], run.events["kind"], run.events["element"])
              if e == "brake"]
    assert [k for _, k in events] == ["engage", "lock", "unlock", "disengage"], events
    np.testing.assert_allclose([t for t, _ in events], [APPLIED, lock, breakaway, RELEASED], rtol=0, atol=1e-9)
    t = run["time"]
    while_held = (t > lock + 1e-6) & (t < breakaway - 1e-6)
    assert np.all(run["ring_speed"][while_held] == 0.0)
    np.testing.assert_allclose(run["set_ring_torque"][while_held], ring_holding, rtol=1e-12)
    # the set turns the ring with -r T, the brake passes that on to the ground: r T less than nothing
    np.testing.assert_allclose(run["brake_torque"][while_held], -ring_holding, rtol=1e-10)
    assert run["ring_speed"][-1] < 0.0  # broken away backwards
    assert np.max(np.abs(willis(run))) < 1e-13 * np.max(np.abs(run["sun_speed"]))
    assert run.summary["energy_relative_residual"] < 1e-9


def test_a_set_ties_shafts_geared_into_bodies():
    """The sun geared to a motor shaft (2:1) and the ring to an output shaft (1:4), each pair one body: the set
    ties the bodies by the shafts' ratios; in the sun's and ring's terms the motor's inertia is 4 J_m on the
    sun, its torque 2 tau_m, the output's 1/16 J_o on the ring; the carrier's speed derived from the motor's
    and the ring's."""
    scene = planetary_scene(force=0.0)
    drawn = scene["drivetrain"]
    drawn["shafts"] = {"motor": {"inertia": "0.05 kg*m^2", "speed": f"{2 * SUN_SPEED} rad/s"},
                       "sun": {"inertia": f"{J_SUN} kg*m^2"}, "carrier": drawn["shafts"]["carrier"],
                       "ring": drawn["shafts"]["ring"], "output": {"inertia": "3.2 kg*m^2"}}
    drawn["torques"] = [{"shaft": "motor", "torque": "2 N*m"}]
    drawn["gears"] = {"primary": {"between": ["motor", "sun"], "ratio": 2},
                      "final": {"between": ["ring", "output"], "ratio": 4}}
    run = simulate(scenario_from_dict(scene))
    accel, torque = uniform((J_SUN + 4 * 0.05, J_CARRIER, J_RING + 3.2 / 16), WEIGHTS, (2 * 2.0, 0.0, 0.0))
    t = run["time"]
    carrier_start = (SUN_SPEED + R * RING_SPEED) / (1 + R)
    np.testing.assert_allclose(run["motor_speed"], 2 * (SUN_SPEED + accel[0] * t), rtol=0, atol=1e-10)
    np.testing.assert_allclose(run["carrier_speed"], carrier_start + accel[1] * t, rtol=0, atol=1e-10)
    np.testing.assert_allclose(run["output_speed"], (RING_SPEED + accel[2] * t) / 4, rtol=0, atol=1e-10)
    np.testing.assert_allclose(run["set_sun_torque"], torque, rtol=1e-12)
    assert np.max(np.abs(willis(run))) < 1e-13 * np.max(np.abs(run["sun_speed"]))
    assert run.summary["energy_relative_residual"] < 1e-9


def housed_scene() -> dict:
    return {"name": "housed-stage", "drivetrain": {
        "shafts": {"a": {"inertia": "0.5 kg*m^2", "speed": "30 rad/s"}, "b": {"inertia": "4 kg*m^2"},
                   "case": {"inertia": "2 kg*m^2", "speed": "-1 rad/s"}},
        "torques": [{"shaft": "a", "torque": "12 N*m"}, {"shaft": "b", "torque": "-20 N*m"}],
        "gears": {"stage": {"between": ["a", "b"], "ratio": 4, "housing": "case"}}},
        "simulation": {"duration": "1 s", "output_interval": "10 ms", **TOL}}


def test_a_stage_on_a_turning_housing_passes_its_reaction_to_the_housing_in_closed_form():
    """w_a - w_case = 4 (w_b - w_case): b's speed derived; the housing bears (r - 1) T, r T at the output."""
    run = simulate(scenario_from_dict(housed_scene()))
    r = 4.0
    accel, torque = uniform((0.5, 4.0, 2.0), (1.0, -r, r - 1.0), (12.0, -20.0, 0.0))
    t = run["time"]
    starts = (30.0, -1.0 + (30.0 + 1.0) / r, -1.0)
    for shaft, a, start in zip(("a", "b", "case"), accel, starts):
        np.testing.assert_allclose(run[f"{shaft}_speed"], start + a * t, rtol=0, atol=1e-10, err_msg=shaft)
    np.testing.assert_allclose(run["stage_input_torque"], torque, rtol=1e-12)
    np.testing.assert_allclose(run["stage_output_torque"], -r * torque, rtol=1e-12)
    np.testing.assert_allclose(run["stage_housing_torque"], (r - 1.0) * torque, rtol=1e-12)
    relation = run["a_speed"] - run["case_speed"] - r * (run["b_speed"] - run["case_speed"])
    assert np.max(np.abs(relation)) < 1e-13 * np.max(np.abs(run["a_speed"]))
    assert run.summary["energy_relative_residual"] < 1e-9


def _with(scene: dict, section: str, name: str, **changes) -> dict:
    out = {**scene, "drivetrain": {**scene["drivetrain"]}}
    out["drivetrain"][section] = {**out["drivetrain"][section], name: {**out["drivetrain"][section][name], **changes}}
    return out


@pytest.mark.parametrize("section, name, changes, key, message", [
    ("planetaries", "set", {"ring": "sun"}, "drivetrain.planetaries.set", "three distinct shafts"),
    ("planetaries", "set", {"teeth": None, "ratio": 1.0}, "drivetrain.planetaries.set.ratio", "must be above 1"),
    ("planetaries", "set", {"teeth": [90, 30]}, "drivetrain.planetaries.set.teeth", "must be above 1"),
    ("planetaries", "set", {"carrier": "arm"}, "drivetrain.planetaries.set.carrier", "there is no shaft 'arm'"),
    ("shafts", "carrier", {"speed": "5 rad/s"}, "drivetrain.shafts.ring.speed", "must be 3.33333333333 rad/s"),
], ids=["a shaft twice", "ratio 1", "the ring smaller", "no such shaft", "speeds that break Willis"])
def test_a_bad_planetary_set_is_one_line_naming_its_key(section, name, changes, key, message):
    scene = _with(planetary_scene(), section, name, **changes)
    scene["drivetrain"]["planetaries"]["set"] = {k: v for k, v in scene["drivetrain"]["planetaries"]["set"].items()
                                                 if v is not None}
    with pytest.raises(ScenarioError, match=message) as caught:
        scenario_from_dict(scene)
    assert caught.value.key == key and "\n" not in str(caught.value)


@pytest.mark.parametrize("changes, key, message", [
    ({"housing": "a"}, "drivetrain.gears.stage.housing", "one of the stage's own"),
    ({"housing": "casing"}, "drivetrain.gears.stage.housing", "there is no shaft 'casing'"),
    ({"efficiency": 0.9}, "drivetrain.gears.stage.efficiency", "give it no efficiency"),
], ids=["its own shaft", "no such shaft", "lossy"])
def test_a_bad_housing_is_one_line_naming_its_key(changes, key, message):
    with pytest.raises(ScenarioError, match=message) as caught:
        scenario_from_dict(_with(housed_scene(), "gears", "stage", **changes))
    assert caught.value.key == key and "\n" not in str(caught.value)


def test_elastic_bearing_against_dymolas_published_trajectories():
    """MSL 4.0's ElasticBearing: every comparison signal within 1e-3 of its range at every reference row more
    than 1 ms from a reference event (the ramp's end at 5 s); the housing's speed (springDamper.w_rel), whose
    ringing Dymola resolves to 2.4e-4 of its range, is the worst."""
    run = simulate(load_scenario(SCENARIOS / "modelica" / "ElasticBearing.yaml"))
    worst = deviations(run, "ElasticBearing", signals("ElasticBearing", run))
    assert max(worst.values()) < 1e-3, worst
    assert run.summary["energy_relative_residual"] < 1e-9

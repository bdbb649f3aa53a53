"""Friction that depends on the slip speed, bearing friction and the one-way clutch, against independent answers.

- Bearing friction (``drivetrain.bearing_frictions``) with a table of the slip speed: a shaft under a torque
  ramp breaks away at peak times its friction at rest and runs up as the closed form of each of the table's
  pieces; a shaft let go at speed runs down through a knot and stops where the closed form does, and stays.
- A clutch whose kinetic friction is a table of the slip speed (Modelica's mu_pos): its slip against an
  independent integration (scipy's DOP853 at rtol 1e-12) at every row, the lock where scipy's slip reaches zero.
- A one-way clutch (``drivetrain.one_way_clutches``): the freewheel catches the driven shaft where the speeds
  meet, both then turn as one; pushed the other way the clutch holds up to its static capacity (peak times
  the friction at rest), beyond it slips at its sliding torque, released it passes nothing.
- Every run's ledger closes with the friction's heat.
- Bad input: one line naming the key.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import drawn
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from hoistsim import simulate
from hoistsim.errors import ScenarioError


def _drawn(duration="1 s", interval="1 ms", **parts):
    return drawn("friction", duration, interval, **parts)


# ----------------------------------------------------------------------------------------------- bearing friction

J, A, B, KNEE = 2.0, 2.0, 0.4, 10.0  # kg*m^2; friction 2 N*m at rest, rising 0.4 N*m per rad/s to 6 N*m at 10 rad/s
PEAK = 1.5


def _bearing(ramp: float, speed: float):
    """A rotor of 2 kg*m^2 on a bearing whose friction is 2 N*m at rest, 6 N*m from 10 rad/s (peak 1.5), under a
    torque ramp (N*m/s) from rest or let go at a speed: one structure, so both cases share a program."""
    return _drawn(duration="10 s", interval="5 ms",
                  shafts={"rotor": {"inertia": f"{J} kg*m^2", "speed": f"{speed} rad/s"}},
                  torques=[{"shaft": "rotor", "torque": [["0 s", "0 N*m"], ["10 s", f"{10 * ramp} N*m"]]}],
                  bearing_frictions={"bearing": {"shaft": "rotor", "peak": PEAK, "torque": [
                      ["0 rad/s", f"{A} N*m"], [f"{KNEE} rad/s", f"{A + B * KNEE} N*m"], ["100 rad/s", "6 N*m"]]}})


def test_bearing_friction_breaks_away_at_its_peak_and_runs_up_as_the_closed_form():
    """Torque 4 t N*m: it holds until 4 t = 1.5 * 2 N*m (t = 0.75 s), then J w' = 4 t - (2 + 0.4 w) up to 10 rad/s
    (a first-order response to a ramp, in closed form), J w' = 4 t - 6 beyond (a parabola)."""
    k = 4.0
    run = simulate(_bearing(ramp=k, speed=0.0))
    breakaway = PEAK * A / k
    unlocks = run.events["time"][run.events["kind"] == "unlock"]
    assert unlocks[0] == pytest.approx(breakaway, abs=1e-9)
    rate = B / J

    def below_knee(t):  # w' + (B/J) w = (k t - A)/J, w(breakaway) = 0
        particular = (k / B) * t - A / B - k * J / B**2
        at_breakaway = (k / B) * breakaway - A / B - k * J / B**2
        return particular - at_breakaway * np.exp(-rate * (t - breakaway))

    knee = brentq(lambda t: below_knee(t) - KNEE, breakaway + 1e-9, 10.0)

    def beyond_knee(t):
        return KNEE + (k / (2 * J)) * (t**2 - knee**2) - (A + B * KNEE) / J * (t - knee)

    t = run.time
    expected = np.where(t < breakaway, 0.0, np.where(t < knee, below_knee(t), beyond_knee(t)))
    np.testing.assert_allclose(run["rotor_speed"], expected, rtol=0, atol=1e-8)
    assert np.all(run["bearing_locked"][t < breakaway] == 1) and np.all(run["bearing_locked"][t > breakaway] == 0)
    assert run.summary["energy_relative_residual"] < 1e-9
    assert run.values["bearing_slip_energy"] > 0


def test_bearing_friction_runs_a_shaft_down_through_its_knot_to_a_stop_and_holds_it():
    """Let go at 16 rad/s: 6 N*m down to 10 rad/s (t = 2 s), then J w' = -(2 + 0.4 w): w = 15 e^(-0.2 (t - 2)) - 5,
    at rest from t = 2 + 5 ln 3 s, where it stays (nothing pushes it).  All the kinetic energy is its heat."""
    run = simulate(_bearing(ramp=0.0, speed=16.0))
    knee = (16.0 - KNEE) * J / (A + B * KNEE)
    rate, offset = B / J, A / B
    stop = knee + math.log((KNEE + offset) / offset) / rate
    locks = run.events["time"][run.events["kind"] == "lock"]
    assert len(locks) == 1 and locks[0] == pytest.approx(stop, abs=1e-9)
    t = run.time
    expected = np.where(t < knee, 16.0 - (A + B * KNEE) / J * t,
                        np.where(t < stop, (KNEE + offset) * np.exp(-rate * (t - knee)) - offset, 0.0))
    np.testing.assert_allclose(run["rotor_speed"], expected, rtol=0, atol=1e-8)
    assert run.values["bearing_slip_energy"] == pytest.approx(0.5 * J * 16.0**2, rel=1e-9)
    assert run.summary["energy_relative_residual"] < 1e-9


# ------------------------------------------------------------------------------ a clutch's friction against slip

MU = [(0.0, 0.4), (5.0, 0.3), (15.0, 0.2)]  # slip speed (rad/s), kinetic friction


def test_a_clutch_whose_friction_falls_with_slip_speed_as_scipy_integrates_it():
    """Shaft a (1 kg*m^2, 20 rad/s) drags shaft b (2 kg*m^2, at rest, loaded by -1 N*m) through a clutch of 0.1 m
    pressed by 300 N, its kinetic friction 0.2 above 15 rad/s of slip, 0.3 at 5 and 0.4 at rest (static 0.45):
    the slip, through both knots, as scipy integrates it; the lock where scipy's slip reaches zero, then one
    body decelerating at 1/3 rad/s^2 (the 1/3 N*m it passes within 13.5 N*m)."""
    run = simulate(_drawn(duration="3 s", interval="2 ms",
                          shafts={"a": {"inertia": "1 kg*m^2", "speed": "20 rad/s"}, "b": {"inertia": "2 kg*m^2"}},
                          torques=[{"shaft": "b", "torque": "-1 N*m"}],
                          clutches={"clutch": {"between": ["a", "b"], "static_friction": 0.45, "effective_radius": "0.1 m",
                                               "force": "300 N",
                                               "kinetic_friction": [[f"{w} rad/s", mu] for w, mu in MU]}}))
    speeds, frictions = (np.array(column) for column in zip(*MU))

    def rates(t, y):
        slip = y[0] - y[1]
        torque = np.interp(abs(slip), speeds, frictions) * 0.1 * 300.0 * np.sign(slip)
        return [-torque / 1.0, (torque - 1.0) / 2.0]

    def meets(t, y):
        return y[0] - y[1]
    meets.terminal = True
    scipy = solve_ivp(rates, (0.0, 3.0), [20.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-12, events=meets,
                      dense_output=True)
    lock = scipy.t_events[0][0]
    assert run.events["time"][run.events["kind"] == "lock"] == pytest.approx([lock], abs=1e-8)
    t = run.time
    before = t < lock
    ours = np.stack([run["a_speed"], run["b_speed"]])
    np.testing.assert_allclose(ours[:, before], scipy.sol(t[before]), rtol=0, atol=1e-8)
    together = scipy.sol(lock)[0] - 1.0 / 3.0 * (t[~before] - lock)
    np.testing.assert_allclose(ours[:, ~before], np.stack([together, together]), rtol=0, atol=1e-8)
    np.testing.assert_allclose(run["clutch_torque"][~before], 1.0 / 3.0, rtol=0, atol=1e-9)
    assert run["clutch_slip"].max() > 15.0 and lock < 2.0  # through both knots, locked a second before the end
    assert run.summary["energy_relative_residual"] < 1e-9


# ------------------------------------------------------------------------------------------------ one-way clutch


def _one_way(peak: float, force: float):
    """In (1 kg*m^2, -0.5 rad/s) driven by 1 N*m; Out (1 kg*m^2, at rest) pushed forwards by 3 N*m from 2 s; a
    one-way clutch (mu 0.5 on 1 m, ``peak``) between them, pressed by ``force`` from 1 s."""
    return _drawn(duration="3 s", interval="1 ms",
                  shafts={"In": {"inertia": "1 kg*m^2", "speed": "-0.5 rad/s"}, "Out": {"inertia": "1 kg*m^2"}},
                  torques=[{"shaft": "In", "torque": "1 N*m"},
                           {"shaft": "Out", "torque": [["0 s", "0 N*m"], ["2 s", "0 N*m"], ["2 s", "3 N*m"]]}],
                  one_way_clutches={"freewheel": {"between": ["In", "Out"], "kinetic_friction": 0.5, "peak": peak,
                                                  "effective_radius": "1 m",
                                                  "force": [["0 s", "0 N"], ["1 s", "0 N"], ["1 s", f"{force} N"]]}})


@pytest.mark.parametrize("peak, force, holds", [(3.0, 1.0, True), (1.5, 1.0, False), (3.0, 0.0, False)],
                         ids=["holding", "slipping", "released"])
def test_a_one_way_clutch_catches_holds_and_lets_overrun(peak, force, holds):
    """In runs up from -0.5 rad/s at 1 rad/s^2 and catches Out at rest at t = 0.5 s (the freewheel locks); both
    then turn as one at 0.5 rad/s^2.  From 2 s Out is pushed by 3 N*m: one body would need 1 N*m from Out to In,
    which the clutch holds within peak * 0.5 * F (1.5 N*m: holding, both at 2 rad/s^2); beyond it (0.75 N*m)
    Out overruns, the clutch sliding at 0.5 N*m (In at 1.5, Out at 2.5 rad/s^2); released, Out runs away at
    3 rad/s^2 and In at 1."""
    run = simulate(_one_way(peak, force))
    t = run.time
    catch = 0.5
    locks = run.events["time"][(run.events["kind"] == "lock") & (run.events["element"] == "freewheel")]
    assert locks[0] == pytest.approx(catch, abs=1e-9)
    together = np.where(t < catch, 0.0, 0.5 * (t - catch))
    at_two = 0.5 * (2.0 - catch)
    sliding = 0.5 * force
    accelerations = (2.0, 2.0) if holds else (1.0 + sliding, 3.0 - sliding)
    expected_in = np.where(t < catch, -0.5 + t, np.where(t <= 2.0, together, at_two + accelerations[0] * (t - 2.0)))
    expected_out = np.where(t < catch, 0.0, np.where(t <= 2.0, together, at_two + accelerations[1] * (t - 2.0)))
    np.testing.assert_allclose(run["In_speed"], expected_in, rtol=0, atol=1e-9)
    np.testing.assert_allclose(run["Out_speed"], expected_out, rtol=0, atol=1e-9)
    assert np.all(run["Out_speed"] >= run["In_speed"] - 1e-12)  # In never overruns Out
    unlocks = run.events["time"][run.events["kind"] == "unlock"]
    assert (len(unlocks) == 0) if holds else (unlocks == pytest.approx([2.0], abs=1e-12))
    late = t > 2.0
    np.testing.assert_allclose(run["freewheel_torque"][late], -1.0 if holds else -sliding, rtol=0, atol=1e-9)
    assert run["freewheel_capacity"][-1] == pytest.approx(peak * 0.5 * force, rel=1e-12)
    assert run.summary["energy_relative_residual"] < 1e-9


# --------------------------------------------------------------------------------------------------- bad input

_SHAFTS = {"a": {"inertia": "1 kg*m^2"}, "b": {"inertia": "1 kg*m^2"}}
_CLUTCH = {"between": ["a", "b"], "effective_radius": "1 m", "force": "10 N", "kinetic_friction": 0.3}


@pytest.mark.parametrize("parts, key, says", [
    ({"bearing_frictions": {"f": {"shaft": "a", "torque": [["0 rad/s", "1 N*m"], ["0 rad/s", "2 N*m"]]}}},
     "drivetrain.bearing_frictions.f.torque", "speeds must increase"),
    ({"bearing_frictions": {"f": {"shaft": "a", "torque": "-1 N*m"}}}, "drivetrain.bearing_frictions.f.torque",
     "negative"),
    ({"bearing_frictions": {"f": {"shaft": "a", "between": ["a", "b"], "torque": "1 N*m"}}},
     "drivetrain.bearing_frictions.f.shaft", "one of them"),
    ({"bearing_frictions": {"f": {"shaft": "c", "torque": "1 N*m"}}}, "drivetrain.bearing_frictions.f.shaft",
     "no shaft 'c'"),
    ({"bearing_frictions": {"f": {"shaft": "a", "torque": "1 N*m", "peak": 0.5}}},
     "drivetrain.bearing_frictions.f.peak", "at least 1"),
    ({"bearing_frictions": {"a": {"shaft": "a", "torque": "1 N*m"}}}, "drivetrain.bearing_frictions.a",
     "not the name of another part"),
    ({"clutches": {"c": {**_CLUTCH, "static_friction": 0.4, "peak": 2}}}, "drivetrain.clutches.c.static_friction",
     "either static_friction or peak"),
    ({"clutches": {"c": _CLUTCH}}, "drivetrain.clutches.c.static_friction", "either static_friction or peak"),
    ({"clutches": {"c": {**_CLUTCH, "static_friction": 0.2}}}, "drivetrain.clutches.c.kinetic_friction",
     "must not exceed static_friction"),
    ({"clutches": {"c": {**_CLUTCH, "peak": 1, "kinetic_friction": [["0 rad/s", 0.3], ["-1 rad/s", 0.2]]}}},
     "drivetrain.clutches.c.kinetic_friction", "speeds must increase"),
    ({"clutches": {"c": {**_CLUTCH, "peak": 1, "kinetic_friction": [["0 rad/s", 0.3], ["1 rad/s", -0.2]]}}},
     "drivetrain.clutches.c.kinetic_friction", "negative"),
    ({"clutches": {"c": {**_CLUTCH, "peak": 1, "kinetic_friction": [["0 rad/s", 0.3], ["1 rad/s", 0.2]],
                         "heating": {"heat_capacity": "500 J/K", "cooling": "1 W/K", "ambient_temperature": "20 degC", "kinetic_friction": [["20 degC", 0.3],
                                                                                       ["200 degC", 0.2]]}}}},
     "drivetrain.clutches.c.kinetic_friction", "give one of them"),
    ({"one_way_clutches": {"w": {**_CLUTCH, "peak": 1, "between": ["a", "ground"]}}},
     "drivetrain.one_way_clutches.w.between", "no shaft 'ground'"),
    ({"one_way_clutches": {"w": {**_CLUTCH, "peak": 1, "between": ["b", "a"]}}, "shafts": {
        "a": {"inertia": "1 kg*m^2"}, "b": {"inertia": "1 kg*m^2", "speed": "1 rad/s"}}},
     "drivetrain.shafts.b.speed", "can never overrun"),
    ({"one_way_clutches": {"w": {**_CLUTCH, "peak": 1, "heating": {"heat_capacity": "500 J/K", "cooling": "1 W/K", "ambient_temperature": "20 degC"}}}},
     "drivetrain.one_way_clutches.w.heating", "not a key of a one-way clutch"),
])
def test_bad_friction_is_one_line_naming_its_key(parts, key, says):
    with pytest.raises(ScenarioError) as err:
        _drawn(**{"shafts": _SHAFTS, **parts})
    assert err.value.key == key and says in err.value.message, (err.value.key, err.value.message)


def test_peak_makes_the_static_friction_of_the_friction_at_rest():
    """Modelica's peak: the static friction is peak times the kinetic friction at zero slip (the table's first row)."""
    scene = _drawn(shafts=_SHAFTS, clutches={"c": {**_CLUTCH, "peak": 2.5, "kinetic_friction": [
        ["0 rad/s", 0.3], ["10 rad/s", 0.2]]}})
    clutch = scene.drivetrain.clutches["c"]
    assert clutch.static_friction == pytest.approx(0.75) and clutch.kinetic_at_rest == 0.3


def test_new_values_of_the_friction_keys_compile_nothing():
    """A bearing friction's table and peak, a one-way clutch's peak, friction and force are traced numbers: runs of
    one structure with new values reuse its program."""
    from hoistsim.machine.core import loop

    simulate(_one_way(3.0, 1.0))
    simulate(_bearing(ramp=4.0, speed=0.0))
    before = loop.trace_count
    simulate(_one_way(1.2, 7.0))
    scene = _bearing(ramp=1.0, speed=3.0)
    scene.drivetrain.bearing_frictions["bearing"] = scene.drivetrain.bearing_frictions["bearing"].model_copy(
        update={"peak": 2.5, "torque": ((0.0, 1.0), (3.0, 2.0), (90.0, 2.5))})
    simulate(scene)
    assert loop.trace_count == before

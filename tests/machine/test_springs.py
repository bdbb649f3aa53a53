"""Torsional springs and dampers (``drivetrain.springs``) against independent answers.

- A shaft on a spring-damper to the ground, let go from an angle: the closed form of the damped oscillation
  (its frequency and its decrement), at every row.
- Modelica's Rotational.Examples.First: an independent integration of its equations (scipy's DOP853, rtol
  1e-12) at every row, and Dymola's published trajectories (tests/data/modelica/First.csv, from
  modelica/MAP-LIB_ReferenceResults) within 1e-3 of each signal's range.
- A spring chain whose clutch locks: the lock where the clutch's sides meet, the spring's energy in the ledger.
- Every run's ledger closes with the springs' strain energy and the dampers' heat.
- Bad input: one line naming the key.
"""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from helpers import SCENARIOS, TESTS, drawn
from modelica_reference import signals

from hoistsim import load_scenario, simulate
from hoistsim.errors import ScenarioError


def _drawn(duration="1 s", interval="1 ms", **parts):
    return drawn("springs", duration, interval, **parts)


def test_a_shaft_on_a_spring_damper_oscillates_as_the_closed_form():
    """J = 0.5, c = 200, d = 2: w_n = 20 rad/s, zeta = 0.1; let go at 0.1 rad, at rest: phi(t) = 0.1 e^(-zeta w_n t)
    (cos w_d t + zeta / sqrt(1 - zeta^2) sin w_d t)."""
    run = simulate(_drawn(shafts={"rotor": {"inertia": "0.5 kg*m^2", "angle": "0.1 rad"}},
                          springs={"shaft": {"between": ["rotor", "ground"], "stiffness": "200 N*m/rad",
                                             "damping": "2 N*m*s/rad"}}))
    t = run.time
    wn, zeta = 20.0, 0.1
    wd = wn * math.sqrt(1 - zeta**2)
    phi = 0.1 * np.exp(-zeta * wn * t) * (np.cos(wd * t) + zeta / math.sqrt(1 - zeta**2) * np.sin(wd * t))
    np.testing.assert_allclose(run["rotor_angle"], phi, rtol=0, atol=1e-10)
    np.testing.assert_allclose(run["shaft_twist"], -phi, rtol=0, atol=1e-10)  # the ground's angle less the rotor's
    # the torque pulls the ground back and the rotor forward: c (0 - phi) + d (0 - w)
    np.testing.assert_allclose(run["shaft_torque"], -200.0 * phi - 2.0 * run["rotor_speed"], rtol=0, atol=1e-8)
    assert run.summary["energy_relative_residual"] < 1e-9
    assert run.ledger["shaft_damping_loss"][2] == pytest.approx(
        0.5 * 200 * 0.1**2 - 0.5 * 200 * phi[-1] ** 2 - 0.5 * 0.5 * run["rotor_speed"][-1] ** 2, rel=1e-8)


def test_a_round_steel_shaft_has_its_torsional_stiffness():
    """G pi (D^4 - D_i^4) / (32 L): a 40 mm steel shaft (G 80 GPa) 0.5 m long, 40 212 N*m/rad; bored to 20 mm,
    15/16 of it; a rotor of 0.5 kg*m^2 on it swings at sqrt(c / J)."""
    solid = {"between": ["rotor", "ground"], "shear_modulus": "80 GPa", "diameter": "40 mm", "length": "0.5 m"}
    hollow = {**solid, "inner_diameter": "20 mm"}
    scene = _drawn(duration="0.2 s", interval="0.1 ms", shafts={"rotor": {"inertia": "0.5 kg*m^2", "speed": "1 rad/s"}},
                   springs={"solid": solid})
    c = 80e9 * math.pi * 0.04**4 / (32 * 0.5)
    assert scene.drivetrain.springs["solid"].spring_rate == pytest.approx(c, rel=1e-15)
    assert _drawn(shafts={"rotor": {"inertia": "1 kg*m^2"}}, springs={"hollow": hollow}).drivetrain.springs[
        "hollow"].spring_rate == pytest.approx(c * 15 / 16, rel=1e-15)
    run = simulate(scene)
    omega = math.sqrt(c / 0.5)
    np.testing.assert_allclose(run["rotor_angle"], np.sin(omega * run.time) / omega, rtol=0, atol=1e-12)


def _first_by_scipy(times):
    """Modelica's First as its equations, solved here: inertia1 geared to inertia2 (one body, J = 2 + 0.1 * 10^2,
    driven by 10 * 10 sin(2 pi 5 t)), the damper from it to the housing, the spring on to inertia3."""
    from scipy.integrate import solve_ivp

    def field(t, y):
        phi2, w2, phi3, w3 = y
        spring = 1e4 * (phi3 - phi2)
        return [w2, (100.0 * math.sin(10 * math.pi * t) - 10.0 * w2 + spring) / 12.0, w3, -spring / 2.0]

    solved = solve_ivp(field, (0.0, times[-1]), [0.0, 0.0, 0.0, 0.0], method="DOP853", t_eval=times, rtol=1e-12,
                       atol=1e-14)
    return solved.y


@pytest.fixture(scope="module", params=["First", "FirstGrounded"])
def first(request):
    run = simulate(load_scenario(SCENARIOS / "modelica" / f"{request.param}.yaml"))
    run.example = request.param
    return run


def test_modelica_first_as_its_equations_solved_independently(first):
    phi2, w2, phi3, w3 = _first_by_scipy(first.time)
    np.testing.assert_allclose(first["inertia2_speed"], w2, rtol=0, atol=1e-8)
    np.testing.assert_allclose(first["inertia3_angle"], phi3, rtol=0, atol=1e-9)
    np.testing.assert_allclose(first["inertia3_speed"], w3, rtol=0, atol=1e-8)
    np.testing.assert_allclose(first["damper_twist"], -phi2, rtol=0, atol=1e-9)
    np.testing.assert_allclose(first["inertia1_speed"], 10.0 * w2, rtol=0, atol=1e-7)
    assert first.summary["energy_relative_residual"] < 1e-9


def test_modelica_first_against_dymolas_published_trajectories(first):
    """Dymola 2020x, DASSL at tolerance 1e-6, MSL 4.0: every comparison signal within 1e-3 of its range at
    every reference row (the largest, inertia3.w, 3.1e-4 of its range: Dymola's own tolerance)."""
    with (TESTS / "data" / "modelica" / f"{first.example}.csv").open() as f:
        rows = list(csv.reader(f))
    names, table = rows[0], np.asarray([[float(v) for v in row] for row in rows[1:]])
    series = signals(first.example, first)  # Modelica's phi_rel, w_rel: flange_b's less flange_a's
    assert names[1:] == list(series)
    for k, signal in enumerate(names[1:], start=1):
        ours = np.interp(table[:, 0], first.time, series[signal])
        worst = np.max(np.abs(ours - table[:, k])) / np.ptp(table[:, k])
        assert worst < 1e-3, (signal, worst)


def test_a_spring_chain_whose_clutch_locks():
    """A shaft at 10 rad/s drives a second through a clutch sliding at 0.4 * 10 N * 1 m; a spring (c 50) ties
    the second to a third at rest.  The clutch locks where its sides meet, each time at one speed (a lock is
    found, never stepped over), and the ledger holds the spring's energy and the clutch's heat."""
    run = simulate(_drawn(duration="3 s",
                          shafts={"a": {"inertia": "1 kg*m^2", "speed": "10 rad/s"}, "b": {"inertia": "1 kg*m^2"},
                                  "c": {"inertia": "1 kg*m^2"}},
                          springs={"link": {"between": ["b", "c"], "stiffness": "50 N*m/rad"}},
                          clutches={"clutch": {"between": ["a", "b"], "static_friction": 0.5,
                                               "kinetic_friction": 0.4, "effective_radius": "1 m", "force": "10 N"}}))
    assert run.summary["energy_relative_residual"] < 1e-9
    locks = run.events["time"][run.events["kind"] == "lock"]
    assert len(locks) >= 1
    for t in locks:
        row = np.flatnonzero(run.time == t)[-1]  # the row just after the lock
        assert run["a_speed"][row] == pytest.approx(run["b_speed"][row], abs=1e-12)
    locked = run["clutch_locked"] == 1
    # while locked, what it passes stays within its capacity, 0.5 * 10 N * 1 m
    assert np.all(np.abs(run["clutch_torque"][locked]) <= 5.0 * (1 + 1e-9))
    assert run.values["clutch_slip_energy"] > 0 and run.ledger["link_strain_energy"][2] > 0


@pytest.mark.parametrize("spring, key, says", [
    ({"between": ["a", "a"], "stiffness": "1 N*m/rad"}, "drivetrain.springs.s.between", "to itself"),
    ({"between": ["a", "nowhere"], "stiffness": "1 N*m/rad"}, "drivetrain.springs.s.between", "no shaft"),
    ({"between": ["a", "ground"], "stiffness": "-1 N*m/rad"}, "drivetrain.springs.s.stiffness", "negative"),
    ({"between": ["a", "ground"], "damping": "-1 N*m*s/rad"}, "drivetrain.springs.s.damping", "negative"),
    ({"between": ["a", "ground"]}, "drivetrain.springs.s.stiffness", "required: a stiffness"),
    ({"between": ["a", "ground"], "stiffness": "0 N*m/rad"}, "drivetrain.springs.s.stiffness", "give a stiffness"),
    ({"between": ["a", "ground"], "shear_modulus": "80 GPa", "diameter": "4 cm"}, "drivetrain.springs.s.length",
     "required"),
    ({"between": ["a", "ground"], "stiffness": "1 N*m/rad", "diameter": "4 cm"}, "drivetrain.springs.s.diameter",
     "not both"),
    ({"between": ["a", "ground"], "stiffness": "1 N*m"}, "drivetrain.springs.s.stiffness", "torsional stiffness"),
    ({"between": ["a", "ground"], "stiffness": "1 N*m/rad", "backlash": "-1 deg"}, "drivetrain.springs.s.backlash",
     "negative"),
])
def test_a_bad_spring_is_one_line_naming_its_key(spring, key, says):
    with pytest.raises(ScenarioError) as err:
        _drawn(shafts={"a": {"inertia": "1 kg*m^2"}}, springs={"s": spring})
    assert err.value.key == key and says in err.value.message, (err.value.key, err.value.message)


@pytest.mark.slow  # a structure of its own to compile (some 8 s)
def test_the_compliant_hoist_slips_where_its_shaft_first_overshoots_the_clutch():
    """scenarios/compliant_hoist.yaml: the motor (0.9 kg*m^2, 500 N*m stall, 300 rpm) on a 40.2 kN*m/rad shaft
    (damping 3) to the clutch's hub (0.05), locked to the pinion side (2.1407 kg*m^2 at the pinion, the load
    185.3 N*m there).  Solved here while locked, the clutch's torque (the shaft's less what the hub's inertia
    takes) first reaches its capacity where hoistsim's clutch first lets go; the rigid model's never does."""
    from scipy.integrate import solve_ivp
    from scipy.optimize import brentq

    from hoistsim.machine.core.element import STICK_TOLERANCE, TORQUE_RESOLUTION

    scene = load_scenario(SCENARIOS / "compliant_hoist.yaml")
    run = simulate(scene)
    spring = scene.drivetrain.springs["motor_shaft"]
    c, d = spring.spring_rate, spring.damping
    ratio = 17 / 90
    driven = 0.05 + (40.0 + 500 * 0.2**2) * ratio**2  # hub, drum and load at the pinion: one body while locked
    load = 500 * 9.81 * 0.2 * ratio
    w0 = 10 * math.pi
    capacity = scene.drivetrain.clutches["clutch"].torque_per_newton * 0.3 * 3201

    def field(t, y):
        phi_m, w_m, phi_h, w_h = y
        shaft = c * (phi_m - phi_h) + d * (w_m - w_h)
        return [w_m, (500 * (1 - w_m / w0) - shaft) / 0.9, w_h, (shaft - load) / driven]

    def clutch_torque(t):
        y = solved.sol(t)
        shaft = c * (y[0] - y[2]) + d * (y[1] - y[3])
        return shaft - 0.05 * (shaft - load) / driven

    solved = solve_ivp(field, (0.0, 0.02), [0.0] * 4, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
    times = np.linspace(0.0, 0.02, 20001)
    first = times[np.argmax([clutch_torque(t) > capacity for t in times])]
    breakaway = brentq(lambda t: clutch_torque(t) - (capacity * (1 + STICK_TOLERANCE) + TORQUE_RESOLUTION),
                       first - 1e-5, first + 1e-5, xtol=1e-15)
    unlocks = run.events["time"][run.events["kind"] == "unlock"]
    assert unlocks[0] == pytest.approx(breakaway, abs=1e-8)
    assert run.summary["energy_relative_residual"] < 1e-9
    assert run["motor_shaft_torque"].max() > capacity > run["clutch_torque"].max() * (1 - 1e-9)
    assert run["load_position"][-1] < -0.1  # it runs back
    rigid = simulate(load_scenario(SCENARIOS / "exercise6_direct_start.yaml"))
    assert rigid["clutch_torque"].max() < 0.82 * capacity and np.all(rigid["clutch_locked"] == 1)


def test_backlash_flight_contact_and_exit_in_closed_form():
    """A rotor (1 kg*m^2) in the middle of a play of 0.2 rad at 2 rad/s, on a spring of 1000 N*m/rad beyond it:
    it flies 0.1 rad (0.05 s), presses for half a period pi sqrt(J / c), leaves at -2 rad/s, flies the whole
    play back (0.1 s) and meets the other side."""
    run = simulate(_drawn(duration="0.5 s", shafts={"rotor": {"inertia": "1 kg*m^2", "speed": "2 rad/s"}},
                          springs={"teeth": {"between": ["ground", "rotor"], "stiffness": "1000 N*m/rad",
                                             "backlash": "0.2 rad"}}))
    half = math.pi * math.sqrt(1.0 / 1000.0)
    expected = [("contact", 0.05), ("separation", 0.05 + half), ("contact", 0.15 + half),
                ("separation", 0.15 + 2 * half), ("contact", 0.25 + 2 * half)]
    got = [(str(k), float(t)) for k, t in zip(run.events["kind"], run.events["time"])]
    assert [k for k, _ in got] == [k for k, _ in expected] + [k for k, _ in got[len(expected):]]
    for (_, t), (_, want) in zip(got, expected):
        assert t == pytest.approx(want, abs=1e-9)
    leaving = np.flatnonzero(run.time == got[1][1])[-1]
    assert run["rotor_speed"][leaving] == pytest.approx(-2.0, abs=1e-9)
    apart = (run.time > got[1][1]) & (run.time < got[2][1])
    assert np.all(run["teeth_torque"][apart] == 0.0) and np.all(run["teeth_contact"][apart] == 0)
    assert np.all(run["teeth_contact"][(run.time > 0.05) & (run.time < got[1][1])] == 1)
    # the solver's error through four contacts, in proportion to its tolerance: 1.3e-9 at rtol 1e-11, 1.9e-8 at
    # 1e-10, 8.9e-11 at 1e-12
    assert run.summary["energy_relative_residual"] < 2e-9


def test_backlash_damping_lets_go_where_the_contact_stops_pressing():
    """With damping (d 10), the contact passes c s + min(c s, d s') (s the strain beyond the play: the damping
    never more than the spring's own torque) and lets go where c s + d s' falls to zero, before the spring is
    back at rest.  Solved here in its two phases (scipy's DOP853 at rtol 1e-12, each phase's end an event):
    2 c s while d s' > c s, then c s + d s'.  The damping never pulls: the torque never changes sign."""
    from scipy.integrate import solve_ivp

    run = simulate(_drawn(duration="0.6 s", shafts={"rotor": {"inertia": "1 kg*m^2", "speed": "2 rad/s"}},
                          springs={"teeth": {"between": ["ground", "rotor"], "stiffness": "1000 N*m/rad",
                                             "damping": "10 N*m*s/rad", "backlash": "0.2 rad"}}))
    c, d = 1000.0, 10.0

    def phase(law, end, start, y0):
        event = lambda t, y: end(y)  # noqa: E731
        event.terminal, event.direction = True, -1
        solved = solve_ivp(lambda t, y: [y[1], -law(y)], (start, start + 1.0), y0, method="DOP853", rtol=1e-12,
                           atol=1e-14, events=event)
        return solved.t_events[0][0], solved.y_events[0][0]

    t1, y1 = phase(lambda y: 2 * c * y[0], lambda y: d * y[1] - c * y[0], 0.0, [0.0, 2.0])
    leave, (strain, speed) = phase(lambda y: c * y[0] + d * y[1], lambda y: c * y[0] + d * y[1], t1, list(y1))
    events = [(str(k), float(t)) for k, t in zip(run.events["kind"], run.events["time"])]
    assert events[0] == ("contact", pytest.approx(0.05, abs=1e-9))
    assert events[1] == ("separation", pytest.approx(0.05 + leave, abs=1e-8))
    row = np.flatnonzero(run.time == events[1][1])[-1]
    assert run["rotor_speed"][row] == pytest.approx(speed, abs=1e-7)
    # leaving, the spring is still strained: that energy is the release's loss, and the ledger holds it
    assert strain > 0.0 and run.summary["energy_relative_residual"] < 1e-9
    # the damping never pulls the sides together: pressed forwards it passes tau >= 0 (pulling the rotor back),
    # backwards tau <= 0, apart nothing
    contact, torque = run["teeth_contact"], run["teeth_torque"]
    assert np.all(torque * contact >= 0.0) and np.all(torque[contact == 0] == 0.0)
    assert set(contact) == {-1, 0, 1}


def test_modelica_backlash_against_dymolas_published_trajectories():
    """Every signal within 1e-3 of its range at every reference row more than 1 ms from one of its events (worst
    1.1e-5), and each contact where a reference event is (Dymola's events are where the strain crosses the play;
    its law lets go without an event where the torque falls to zero, ours records that as a separation)."""
    run = simulate(load_scenario(SCENARIOS / "modelica" / "Backlash.yaml"))
    with (TESTS / "data" / "modelica" / "Backlash.csv").open() as f:
        rows = list(csv.reader(f))
    names, table = rows[0], np.asarray([[float(v) for v in row] for row in rows[1:]])
    events = np.unique(table[1:, 0][np.diff(table[:, 0]) == 0.0])
    far = np.min(np.abs(table[:, :1] - events[None, :]), axis=1) > 1e-3
    series = signals("Backlash", run)
    for k, signal in enumerate(names[1:], start=1):
        ours = np.interp(table[:, 0], run.time, series[signal])
        worst = np.max(np.abs(ours - table[:, k])[far]) / np.ptp(table[:, k])
        assert worst < 1e-3, (signal, worst)
    contacts = run.events["time"][run.events["kind"] == "contact"]
    assert len(contacts) >= 10
    for t in contacts:
        assert np.min(np.abs(events - t)) < 1e-4, t
    assert run.summary["energy_relative_residual"] < 1e-7

"""The closed-form solution, checked against an independent numerical integration,
the energy balance, and limits that can be worked out by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hoistsim.references import exact as exact_module
from hoistsim.references.exact import ExactEvent, ExpPoly, first_crossing, solve_exact
from hoistsim.references.model import LOCKED, OPEN, SLIP_FORWARD, Drivetrain, Machine
from hoistsim.references.scipy_reference import solve_with_scipy

G = 9.81
W0 = 300.0 * 2.0 * math.pi / 60.0  # 300 rpm


def exercise6(mass=500.0, fs=0.3, fk=0.1):
    """The exercise-6 hoist reduced to the clutch shafts, with a chosen load mass."""
    tau, radius = 90.0 / 17.0, 0.2
    rest_of_side_b = 2.140740740740741 - 500.0 * radius**2 / tau**2  # pinion, wheel, drum
    return Drivetrain(
        motor_inertia=0.9, output_inertia=rest_of_side_b + mass * radius**2 / tau**2,
        stall_torque=500.0, no_load_speed=W0, load_torque=mass * G * radius / tau,
        clutch_constant=0.5205643482935497, static_friction=fs, kinetic_friction=fk,
        ratio=tau, rope_radius=radius, load_weight=mass * G,
    )


# --------------------------------------------------------------------------------------
# An independent reference: the same hybrid model integrated numerically (DOP853) with
# solve_ivp event location and explicit restarts.
# --------------------------------------------------------------------------------------


def reference(d, times, forces, duration, wa0=0.0, wb0=0.0, release=None):
    """DOP853 at rtol = atol = 1e-12 with a bounded step (its dense output is then trustworthy)."""
    events, evaluate, pieces, _ = solve_with_scipy(d, times, forces, duration, wa0, wb0, release, max_step=0.05)
    return events, evaluate, pieces


CASES = {
    # force ramps in, the clutch slips, locks; force dips: unlock; force back: lock
    "ramp_down_up": (exercise6(), [0, 0.5, 1.5, 2.0, 2.5, 3.0], [0, 6000, 6000, 500, 500, 6000], 4.0, {},
                     ["lock", "unlock", "lock"]),
    # static == kinetic friction: the unlock restarts tangent to the slip surface
    "tangent_restart": (exercise6(fs=0.2, fk=0.2), [0, 0.5, 1.5, 2.0, 2.5, 3.0],
                        [0, 6000, 6000, 500, 500, 6000], 4.0, {}, ["lock", "unlock", "lock"]),
    # engage at speed: motor running, drum at rest, constant force
    "engage_at_speed": (exercise6(), [0], [5000], 2.0, {"wa0": 0.9 * W0}, ["lock"]),
    # kinetic torque below the load torque: the load runs back while the clutch slips
    "run_back": (exercise6(), [0], [1500], 2.0, {}, []),
    # drum held while the motor spins up against the slipping clutch, then released
    "brake": (exercise6(mass=200.0), [0], [2500], 3.0, {"release": 0.5}, ["brake_release", "lock"]),
    # drum overruns the motor: slip closes at low speed and reverses
    "reversal": (exercise6(), [0], [1000], 1.0, {"wb0": 10.0}, ["reversal"]),
    # open, engage on a force step, lock, release the force: unlock, disengage
    "open_engage": (exercise6(), [0, 0.3, 0.3, 1.5, 1.7], [0, 0, 6000, 6000, 0], 2.5, {},
                    ["engage", "lock", "unlock", "disengage"]),
}


def run_exact(d, times, forces, duration, kw):
    return solve_exact(d, times, forces, duration, initial_motor_speed=kw.get("wa0", 0.0),
                       initial_output_speed=kw.get("wb0", 0.0), brake_release=kw.get("release"))


@pytest.fixture(scope="module", params=sorted(CASES))
def case(request):
    d, times, forces, duration, kw, kinds = CASES[request.param]
    ref_events, ref_eval, ref_pieces = reference(
        d, times, forces, duration, kw.get("wa0", 0.0), kw.get("wb0", 0.0), kw.get("release"))
    return d, duration, kinds, run_exact(d, times, forces, duration, kw), ref_events, ref_eval, ref_pieces


def test_events_match_reference(case):
    d, duration, kinds, sol, ref_events, _, _ = case
    assert [e.kind for e in sol.events] == kinds
    assert [k for _, k in ref_events] == kinds
    for e, (t_ref, _) in zip(sol.events, ref_events):
        assert abs(e.time - t_ref) < 1e-10


def test_trajectory_matches_reference(case):
    d, duration, kinds, sol, _, ref_eval, ref_pieces = case
    ts = np.linspace(0.0, duration, 157)
    ours = sol.evaluate(ts)
    ref = ref_eval(ts)
    for row, key in enumerate(("motor_speed", "output_speed", "load_position")):
        np.testing.assert_allclose(ours[key], ref[row], rtol=0, atol=1e-9 * (1 + np.abs(ref[row]).max()))
    for row, key in ((3, "clutch_energy"), (4, "motor_work")):
        np.testing.assert_allclose(ours[key], ref[row], rtol=0, atol=1e-9 * (1 + np.abs(ref[row]).max()))
    # modes agree away from the switching instants
    switches = np.array([e.time for e in sol.events] + [-1.0])
    far = np.all(np.abs(ts[:, None] - switches[None, :]) > 1e-6, axis=1)
    modes = [[p[3] for p in ref_pieces if p[0] <= t][-1] for t in ts[far]]
    np.testing.assert_array_equal(ours["mode"][far], modes)


def test_energy_balance_closes(case):
    d, duration, kinds, sol, _, _, _ = case
    v = sol.evaluate(np.linspace(0.0, duration, 2001))
    ke = d.kinetic_energy(v["motor_speed"], v["output_speed"])
    balance = v["motor_work"] - (ke - ke[0] + d.load_weight * v["load_position"] + v["clutch_energy"])
    scale = max(np.abs(v["motor_work"]).max(), np.abs(ke).max(), v["clutch_energy"].max())
    assert np.abs(balance).max() < 1e-10 * scale
    assert np.all(np.diff(v["clutch_energy"]) >= -1e-12 * scale)


def test_final_and_summary_values(case):
    d, duration, kinds, sol, _, _, _ = case
    end = sol.evaluate(np.array([duration]))
    for key, value in sol.final.items():
        assert end[key][0] == value
    assert sol.slip_energy == sol.final["clutch_energy"]
    locks = [e.time for e in sol.events if e.mode == LOCKED]
    assert (math.isnan(sol.lockup_time) and not locks) or sol.lockup_time == locks[0]


# --------------------------------------------------------------------------------------
# Limits worked out by hand
# --------------------------------------------------------------------------------------


def test_huge_force_locks_at_start_and_follows_the_locked_exponential():
    d = exercise6()
    sol = solve_exact(d, [0.0], [1e7], 3.0)
    assert sol.events == [] and sol.lockup_time == 0.0 and sol.slip_energy == 0.0
    t = np.linspace(0.0, 3.0, 301)
    v = sol.evaluate(t)
    beta = d.stall_torque / d.no_load_speed
    w_ss, lam = (d.stall_torque - d.load_torque) / beta, beta / (d.motor_inertia + d.output_inertia)
    w = -w_ss * np.expm1(-lam * t)
    np.testing.assert_allclose(v["motor_speed"], w, rtol=1e-13, atol=1e-13)
    np.testing.assert_array_equal(v["motor_speed"], v["output_speed"])
    x = d.rope_radius / d.ratio * w_ss * (t + np.expm1(-lam * t) / lam)
    np.testing.assert_allclose(v["load_position"], x, rtol=1e-12, atol=1e-15)
    assert np.all(v["mode"] == LOCKED)


def test_zero_force_is_open_with_free_dynamics():
    d = exercise6()
    sol = solve_exact(d, [0.0, 1.0], [0.0, 0.0], 2.0)
    assert sol.events == [] and math.isnan(sol.lockup_time)
    t = np.linspace(0.0, 2.0, 201)
    v = sol.evaluate(t)
    lam = d.stall_torque / (d.no_load_speed * d.motor_inertia)
    free_motor = -d.no_load_speed * np.expm1(-lam * t)
    np.testing.assert_allclose(v["motor_speed"], free_motor, rtol=1e-13, atol=1e-13)
    falling = -d.load_torque / d.output_inertia * t
    np.testing.assert_allclose(v["output_speed"], falling, rtol=1e-13, atol=1e-13)
    np.testing.assert_allclose(v["load_position"], -d.rope_radius / d.ratio * d.load_torque / d.output_inertia
                               * t**2 / 2, rtol=1e-12, atol=1e-15)
    assert np.all(v["mode"] == OPEN) and np.all(v["clutch_energy"] == 0.0)


def test_exercise6_rest_start_below_kinetic_lift_runs_the_load_back():
    # F = 1500 N: T_s = 234 N*m cannot hold the start (T_c = 407 N*m), and
    # T_k = 78 N*m < T_L = 185 N*m cannot lift while slipping.
    d = exercise6()
    sol = solve_exact(d, [0.0], [1500.0], 2.0)
    assert sol.events == [] and sol.final["mode"] == SLIP_FORWARD
    v = sol.evaluate(np.linspace(0.0, 2.0, 101))
    assert np.all(np.diff(v["load_position"]) < 0.0) and np.all(v["output_speed"][1:] < 0.0)


def test_engage_at_speed_locks_once_with_equal_speeds():
    d = exercise6()
    sol = solve_exact(d, [0.0], [5000.0], 2.0, initial_motor_speed=0.9 * W0)
    assert [(e.kind, e.mode) for e in sol.events] == [("lock", LOCKED)]
    t_lock = sol.lockup_time
    at = sol.evaluate(np.array([t_lock, t_lock - 1e-9, t_lock + 1e-3]))
    assert at["motor_speed"][0] == at["output_speed"][0]
    assert abs(at["motor_speed"][1] - at["output_speed"][1]) < 1e-6
    assert list(at["mode"]) == [LOCKED, SLIP_FORWARD, LOCKED]
    # just before the lock the slip is tiny and still positive
    assert at["motor_speed"][1] > at["output_speed"][1]


def test_brake_events_and_held_drum():
    d = exercise6(mass=200.0)
    sol = solve_exact(d, [0.0], [2500.0], 3.0, brake_release=0.5)
    assert [e.kind for e in sol.events] == ["brake_release", "lock"]
    assert sol.events[0] == ExactEvent(0.5, "brake_release", SLIP_FORWARD)
    v = sol.evaluate(np.linspace(0.0, 0.5, 51, endpoint=False))
    assert np.all(v["output_speed"] == 0.0) and np.all(v["load_position"] == 0.0)
    # released at the start: the event is at t = 0 and the drum is free at once
    sol0 = solve_exact(d, [0.0], [2500.0], 1.0, brake_release=0.0)
    assert (sol0.events[0].time, sol0.events[0].kind) == (0.0, "brake_release")
    assert sol0.events[0].mode == sol0.evaluate(np.array([0.0]))["mode"][0]
    # never released within the run: no event, the drum never moves
    never = solve_exact(d, [0.0], [2500.0], 1.0, brake_release=5.0)
    assert never.events == [] and never.final["output_speed"] == 0.0
    # locked to the held drum from rest stays locked through the release
    held = solve_exact(exercise6(), [0.0], [6000.0], 1.0, brake_release=0.5)
    assert [(e.kind, e.mode) for e in held.events] == [("brake_release", LOCKED)] and held.lockup_time == 0.0
    with pytest.raises(ValueError):
        solve_exact(d, [0.0], [2500.0], 1.0, brake_release=0.5, initial_output_speed=1.0)


def test_restart_on_switching_surface_never_refires():
    # f_s == f_k: after the unlock the slip starts with zero value and zero slope.
    d = exercise6(fs=0.2, fk=0.2)
    sol = solve_exact(d, [0, 0.5, 1.5, 2.0, 2.5, 3.0], [0, 6000, 6000, 500, 500, 6000], 4.0)
    assert [e.kind for e in sol.events] == ["lock", "unlock", "lock"]
    t_unlock = sol.events[1].time
    v = sol.evaluate(t_unlock + np.array([1e-6, 1e-3, 1e-1]))
    assert np.all(v["motor_speed"] > v["output_speed"]) and np.all(v["mode"] == SLIP_FORWARD)


def test_chattering_cap():
    with pytest.raises(RuntimeError, match="chattering"):
        solve_exact(exercise6(), [0, 0.5, 1.5, 2.0, 2.5, 3.0], [0, 6000, 6000, 500, 500, 6000], 4.0,
                    max_events=2)


def test_first_crossing_on_and_off_the_surface():
    g = ExpPoly.poly(0.0, 1.0, -1.0)  # u - u^2: starts on the surface, rises, returns at u = 1
    assert first_crossing(g, 2.0) == pytest.approx(1.0, abs=1e-15)
    assert first_crossing(g, 0.5) is None
    assert first_crossing(-g, 2.0) == 0.0  # leaves the admissible side at once
    # (u - 1)^2 - 1e-10 dips below zero for 2e-5 s only, well inside one grid cell
    dip = ExpPoly.poly(1.0 - 1e-10, -2.0, 1.0)
    assert first_crossing(dip, 2.9) == pytest.approx(1.0 - 1e-5, abs=1e-10)
    e = ExpPoly.exp(2.0, 3.0) - 1.0  # 2 exp(-3u) - 1
    assert first_crossing(e, 1.0) == pytest.approx(math.log(2.0) / 3.0, abs=1e-15)


def test_exppoly_integral_is_accurate_for_tiny_arguments():
    e = ExpPoly({(0, 20.0): 1.0, (2, 40.0): 3.0})
    u = 1e-9
    expected = -np.expm1(-20.0 * u) / 20.0 + 3.0 * u**3 / 3.0 * (1 - 40.0 * u * 3 / 4)
    assert e.integral(u) == pytest.approx(expected, rel=1e-14)


def test_exact_from_scenario_reads_the_scene():
    from helpers import scene

    s = scene(force=[["0 s", "0 N"], ["0.3 s", "0 N"], ["0.3 s", "6000 N"]], motor_speed="3 rad/s",
              duration="1.5 s")
    d = Machine.from_scenario(s).reduced()
    sol = exact_module.exact_from_scenario(s)
    direct = solve_exact(d, [0.0, 0.3, 0.3], [0.0, 0.0, 6000.0], 1.5, initial_motor_speed=3.0)
    assert sol.events == direct.events and sol.final == direct.final
    braked = scene(force=[["0 s", "0 N"], ["0.3 s", "0 N"], ["0.3 s", "6000 N"]], brake="0.3 s")
    kinds = [e.kind for e in exact_module.exact_from_scenario(braked).events]
    assert kinds[:2] == ["brake_release", "engage"]


def test_steady_lift_starts_at_constant_speed():
    from helpers import EXERCISE6

    from hoistsim import scenario_from_dict

    data = dict(EXERCISE6, initial={"steady_lift": True})
    sol = exact_module.exact_from_scenario(scenario_from_dict(data))
    speeds = sol.evaluate(np.linspace(0.0, 2.0, 5))["motor_speed"]
    np.testing.assert_allclose(speeds, speeds[0], rtol=1e-12)
    assert sol.lockup_time == 0.0 and sol.events == []

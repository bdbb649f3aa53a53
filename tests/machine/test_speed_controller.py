"""A speed controller (drivetrain.speed_controllers, Modelica's LimPID), against independent answers.

- Modelica's PID_Controller (scenarios/modelica/PID_Controller.yaml) against Dymola's published trajectories:
  the integral's state, the drive's angle and speed, the reference, the spring's twist and its rate within 1e-3
  of their ranges, and the limiter's two corners at Dymola's events.
- A PID loop on a rigid inertia, within its limits: a linear system (its characteristic equation
  s^2 + (k/J) s + k/(J T_i) = 0 without the derivative part), solved exactly by the matrix exponential.
- The ledger (the controller's work = the kinetic energy + the spring's and damper's + the load's), the time at
  the limit, and bad input: one line naming the key, nothing written.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import SCENARIOS, part_keys_set, refused_in_one_line
from modelica_reference import deviations, reference, signals
from scipy.linalg import expm

from hoistsim import load_scenario, scenario_from_text, simulate

PID = SCENARIOS / "modelica" / "PID_Controller.yaml"


@pytest.fixture(scope="module")
def pid_controller():
    return simulate(load_scenario(PID))


def test_pid_controller_against_dymolas_published_trajectories(pid_controller):
    """Measured: PI.I.y 1.5e-5, inertia1.phi 2e-8, .w 5.2e-7, integrator.y 3e-15, spring.phi_rel 8.6e-6, .w_rel
    5.9e-5 of their ranges; the limiter's corners within 1e-7 s of Dymola's events (its tolerance)."""
    run = pid_controller
    worst = deviations(run, "PID_Controller", signals("PID_Controller", run))
    assert max(worst.values()) < 2e-4, worst
    times = reference("PID_Controller")["time"]
    dymola = np.unique(times[1:][np.diff(times) == 0.0])
    corners = [dymola[np.argmin(np.abs(dymola - t))] for t in (2.1018, 3.4951)]  # its events but the table's
    kinds = list(run.instants["kind"])
    ours = [run.instants["time"][kinds.index("PI_saturate")], run.instants["time"][kinds.index("PI_desaturate")]]
    np.testing.assert_allclose(ours, corners, rtol=0, atol=2e-7)
    assert run.summary["PI_saturated_time"] == pytest.approx(ours[1] - ours[0], rel=1e-12)
    assert run.summary["energy_relative_residual"] < 1e-10


def test_it_starts_steady_holding_its_load(pid_controller):
    """``output: -10 N*m``: the integral set so that the controller holds the load's 10 N*m at rest (Modelica's
    SteadyState), so nothing moves before the reference does at 0.5 s."""
    run = pid_controller
    before = run.time < 0.5
    assert run["PI_integral"][0] == pytest.approx(-0.1, rel=1e-14)  # y = k (e + I): -10 = 100 (0 + I)
    assert np.max(np.abs(run["inertia1_speed"][before])) < 1e-12
    assert np.max(np.abs(run["PI_output"][before] + 10.0)) < 1e-9


def _rigid_loop(derivative_time: float, torque_lag: float = 0.0) -> str:
    return f"""
name: pid-on-an-inertia
drivetrain:
  shafts:
    drive: {{inertia: 2 kg*m^2}}
  speed_controllers:
    speed:
      measures: drive
      reference: [[0 s, 3 rad/s], [1 s, 3 rad/s]]
      gain: 40 N*m*s/rad
      integral_time: 0.25 s
      derivative_time: {derivative_time} s
      derivative_filter: 8
      derivative_setpoint_weight: 0.5
      max_torque: 1000 N*m
      torque_lag: {torque_lag} s
simulation:
  duration: 1.5 s
  output_interval: 1 ms
  rtol: 1e-11
  atol: 1e-12
"""


@pytest.mark.parametrize("derivative_time, torque_lag", [(0.0, 0.0), (0.05, 0.0), (0.0, 0.02)],
                         ids=["PI", "PID", "PI with a torque lag"])
def test_a_loop_on_an_inertia_within_its_limits_is_the_matrix_exponential(derivative_time, torque_lag):
    """J w' = k (r - w + I + D), I' = (r - w) / T_i, D = N_d (w_d r - w - z), z' = N_d (w_d r - w - z) / T_d (and
    the torque lagging, T_c tau' = y - tau): with r constant a linear system, its exact solution expm(M t) z0;
    without D, the error's decay is the roots of s^2 + (k/J) s + k/(J T_i)."""
    run = simulate(scenario_from_text(_rigid_loop(derivative_time, torque_lag)))
    inertia, k, ti, nd, wd, r = 2.0, 40.0, 0.25, 8.0, 0.5, 3.0
    if torque_lag > 0.0:  # (w, I, tau, 1): T_c tau' = k (r - w + I) - tau, tau starting at y(0) = k r
        tc = torque_lag
        m = np.array([[0.0, 0.0, 1 / inertia, 0.0], [-1 / ti, 0.0, 0.0, r / ti],
                      [-k / tc, k / tc, -1 / tc, k * r / tc], [0.0, 0.0, 0.0, 0.0]])
        start = np.array([0.0, 0.0, k * r, 1.0])
    elif derivative_time == 0.0:  # (w, I, 1)
        m = np.array([[-k / inertia, k / inertia, k * r / inertia], [-1 / ti, 0.0, r / ti], [0.0, 0.0, 0.0]])
        start = np.array([0.0, 0.0, 1.0])
    else:  # (w, I, z, 1), z starting at rest: z0 = w_d r - w0, the derivative part 0
        td = derivative_time
        m = np.array([[-k * (1 + nd) / inertia, k / inertia, -k * nd / inertia, k * (r + nd * wd * r) / inertia],
                      [-1 / ti, 0.0, 0.0, r / ti],
                      [-nd / td, 0.0, -nd / td, nd * wd * r / td],
                      [0.0, 0.0, 0.0, 0.0]])
        start = np.array([0.0, 0.0, wd * r, 1.0])
    exact = np.array([expm(m * t) @ start for t in run.time])
    np.testing.assert_allclose(run["drive_speed"], exact[:, 0], rtol=0, atol=1e-8 * r)
    np.testing.assert_allclose(run["speed_integral"], exact[:, 1], rtol=0, atol=1e-8 * r)
    assert run.summary["speed_saturated_time"] == 0.0 and run.summary["energy_relative_residual"] < 1e-10
    if torque_lag > 0.0:
        np.testing.assert_allclose(run["speed_torque"], exact[:, 2], rtol=0, atol=1e-8 * k * r)
    elif derivative_time == 0.0:
        roots = np.roots([1.0, k / inertia, k / (inertia * ti)])
        assert sorted(np.linalg.eigvals(m[:2, :2]).real) == pytest.approx(sorted(roots.real), rel=1e-12)


def test_the_ledger_takes_the_controllers_torque_as_work(pid_controller):
    run = pid_controller
    work = run.energy_balance["PI_work"]
    power = run["PI_output"] * run["inertia1_speed"]
    assert work == pytest.approx(np.trapezoid(power, run.time), rel=1e-5)  # the rows' sum: a check of the state
    assert run.energy_balance["relative_residual"] < 1e-10


@pytest.mark.parametrize("change, key, says", [
    ({"reference": None}, "drivetrain.speed_controllers.PI.reference", "required"),
    ({"min_torque": "20 N*m"}, "drivetrain.speed_controllers.PI.min_torque", "must leave room"),
    ({"output": "-15 N*m"}, "drivetrain.speed_controllers.PI.output", "outside the limits"),
    ({"integral": -0.1}, "drivetrain.speed_controllers.PI.output", "not both"),
    ({"measures": "motor"}, "drivetrain.speed_controllers.PI.measures", "no shaft 'motor'"),
])
def test_bad_input_names_its_key(change, key, says, tmp_path):
    refused_in_one_line(PID, part_keys_set("speed_controllers", "PI", change), key, says, tmp_path)

@pytest.mark.parametrize("distance, speed, acceleration, shape", [
    (np.pi / 2, 1.0, 1.0, "trapezoid"), (0.5, 1.0, 1.0, "triangle"), (-3.0, 1.0, 0.5, "trapezoid")])
def test_a_kinematic_ptp_reference_moves_its_distance_within_its_limits(distance, speed, acceleration, shape):
    """Modelica's KinematicPTP integrated: the speed's integral is the distance; no faster than max_speed, no
    steeper than max_acceleration; a triangle where the distance leaves no time at the most speed."""
    from hoistsim.scenario.schema_speed_reference import KinematicPtpSpec

    times, speeds = map(np.asarray, KinematicPtpSpec(distance=distance, max_speed=speed,
                                                     max_acceleration=acceleration, start=0.5).table())
    assert np.trapezoid(speeds, times) == pytest.approx(distance, rel=1e-14)
    assert np.max(np.abs(speeds)) <= speed * (1 + 1e-15)
    slopes = np.diff(speeds)[np.diff(times) > 0] / np.diff(times)[np.diff(times) > 0]
    assert np.max(np.abs(slopes)) == pytest.approx(acceleration, rel=1e-14)
    assert (times[2] == times[3]) == (shape == "triangle") and times[1] == 0.5


def test_an_s_curve_reference_is_its_acceleration_integrated_exactly():
    """{s_curve: {speed 10 rad/s, acceleration 5 rad/s^2, jerk 20 rad/s^3, from 0.2 s, 1 s at speed}}: the
    acceleration a table of time (its corners segment boundaries), the speed its integral, a state: at every row
    the piecewise-quadratic closed form to 1e-12, the speed reached and no acceleration or jerk above its limits."""
    from hoistsim.scenario.schema_speed_reference import SCurveSpec

    text = _rigid_loop(0.0).replace("reference: [[0 s, 3 rad/s], [1 s, 3 rad/s]]", "reference: {s_curve: {speed: "
                                    "10 rad/s, acceleration: 5 rad/s^2, jerk: 20 rad/s^3, start: 0.2 s, hold: 1 s}}")
    run = simulate(scenario_from_text(text.replace("duration: 1.5 s", "duration: 6 s")))
    times, accelerations = map(np.asarray, SCurveSpec(speed=10, acceleration=5, jerk=20, start=0.2, hold=1).table())

    def speed(t):
        out = 0.0
        for t0, t1, a0, a1 in zip(times[:-1], times[1:], accelerations[:-1], accelerations[1:]):
            if t > t0 and t1 > t0:
                h = min(t, t1) - t0
                out += a0 * h + 0.5 * (a1 - a0) / (t1 - t0) * h * h
        return out

    exact = np.array([speed(t) for t in run.time])
    np.testing.assert_allclose(run["speed_reference"], exact, rtol=0, atol=1e-12 * 10)
    assert np.max(exact) == pytest.approx(10.0, rel=1e-14) and exact[-1] == pytest.approx(0.0, abs=1e-12)
    slopes = np.diff(accelerations)[np.diff(times) > 0] / np.diff(times)[np.diff(times) > 0]
    assert np.max(np.abs(accelerations)) == 5.0 and np.max(np.abs(slopes)) == pytest.approx(20.0, rel=1e-14)

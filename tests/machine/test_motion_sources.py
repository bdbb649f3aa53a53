"""Prescribed motion (drivetrain.motion_sources): a shaft driven at a speed, an angle or an acceleration, against
closed forms.

- A speed ramp driving an inertia through a spring: the far inertia's angle and the source's torque in closed
  form (phi_b = 5 t^2 - 0.1 + 0.1 cos 10 t, T = J_a a + k (phi_a - phi_b) = 30 - 10 cos 10 t).
- An angle table (a kinked reference: the speed jumps at the knots): the shaft's angle is the table; the far
  inertia's in closed form; the ledger closes with the jumps' impulses booked to the source.
- An acceleration with a harmonic: the speed its integral, from the shaft's own start.
- Modelica's filters (exact=false): a speed through a first-order lag in closed form, an angle through the
  Bessel filter against an independent scipy integration of the filter alone.
- A friction clutch that a driven shaft drags: the slip, the lock at the closed form's instant, the heat and
  the torque the source takes slipping and locked; a speed step carried by no friction coupling.
- Bad input: one line naming the key, nothing written.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import part_keys_set, refused_in_one_line
from scipy.integrate import solve_ivp

from hoistsim import scenario_from_text, simulate

SETTINGS = """simulation:
  duration: 3 s
  output_interval: 5 ms
  rtol: 1e-10
  atol: 1e-12
"""


def _scene(sources: str, name: str) -> str:
    """Three driven shafts, two of them pulling an inertia through a spring (k 100 N*m/rad, J 1 kg*m^2)."""
    return f"""name: {name}
drivetrain:
  shafts:
    a: {{inertia: 2 kg*m^2}}
    b: {{inertia: 1 kg*m^2, angle: 0 rad}}
    c: {{inertia: 2 kg*m^2}}
    d: {{inertia: 1 kg*m^2, angle: 0 rad}}
    e: {{inertia: 3 kg*m^2, speed: 1 rad/s}}
  springs:
    spring_ab: {{between: [a, b], stiffness: 100 N*m/rad}}
    spring_cd: {{between: [c, d], stiffness: 100 N*m/rad}}
  motion_sources:
{sources}
{SETTINGS}"""


EXACT = _scene("""    by_speed: {shaft: a, speed: [[0 s, 0 rad/s], [1 s, 10 rad/s], [2 s, 10 rad/s]]}
    by_angle: {shaft: c, angle: [[0 s, 0.5 rad], [1 s, 1.5 rad], [2 s, 1.5 rad]]}
    by_acceleration: {shaft: e, acceleration: {offset: 1 rad/s^2, harmonics: [{amplitude: 2 rad/s^2, frequency: 1 Hz}]}}
""", "exact-sources")
FILTERED = _scene("""    by_speed:
      {shaft: a, speed: [[0 s, 0 rad/s], [1 s, 10 rad/s], [2 s, 10 rad/s]], filter_frequency: 2 Hz}
    by_angle: {shaft: c, angle: [[0 s, 0.5 rad], [1 s, 1.5 rad], [2 s, 1.5 rad]], filter_frequency: 2 Hz}
    by_acceleration: {shaft: e, acceleration: 0 rad/s^2}
""", "filtered-sources")


@pytest.fixture(scope="module")
def exact():
    return simulate(scenario_from_text(EXACT))


@pytest.fixture(scope="module")
def filtered():
    return simulate(scenario_from_text(FILTERED))


def test_a_speed_ramp_through_a_spring_is_its_closed_form(exact):
    run, t = exact, exact.time
    ramp = t < 1.0
    np.testing.assert_allclose(run["a_speed"][ramp], 10.0 * t[ramp], rtol=0, atol=1e-12)
    np.testing.assert_allclose(run["b_angle"][ramp], 5 * t[ramp]**2 - 0.1 + 0.1 * np.cos(10 * t[ramp]), rtol=0,
                               atol=1e-9)
    # the torque it takes: the shaft's inertia times the ramp's acceleration, and the spring's pull (its first
    # row too: the ramp's slope, not a half of it, at the knot)
    np.testing.assert_allclose(run["by_speed_torque"][ramp], 30.0 - 10.0 * np.cos(10 * t[ramp]), rtol=0, atol=1e-7)
    assert run["by_speed_torque"][0] == pytest.approx(20.0, abs=1e-9)
    np.testing.assert_allclose(run["a_speed"][t >= 1.0], 10.0, rtol=0, atol=1e-12)


def test_an_angle_table_is_the_shafts_angle_and_its_kinks_jump_the_speed(exact):
    run, t = exact, exact.time
    np.testing.assert_allclose(run["c_angle"], np.interp(t, [0, 1, 2], [0.5, 1.5, 1.5]), rtol=0, atol=1e-12)
    assert run["c_speed"][t < 1.0] == pytest.approx(1.0, abs=1e-12)
    assert run["c_speed"][t >= 1.0] == pytest.approx(0.0, abs=1e-12)
    # the far inertia starts at 0 against the source's 0.5 rad: phi_d = 0.5 + t - 0.5 cos 10 t - 0.1 sin 10 t
    before = t < 1.0
    np.testing.assert_allclose(run["d_angle"][before], 0.5 + t[before] - 0.5 * np.cos(10 * t[before])
                               - 0.1 * np.sin(10 * t[before]), rtol=0, atol=1e-9)
    assert run["by_angle_torque"][0] == pytest.approx(50.0, abs=1e-9)  # the spring pre-twisted by 0.5 rad


def test_an_acceleration_drives_the_shaft_on_from_its_own_speed(exact):
    t = exact.time
    speed = 1.0 + t + (1.0 - np.cos(2 * np.pi * t)) / np.pi
    np.testing.assert_allclose(exact["e_speed"], speed, rtol=0, atol=1e-10)
    accel = 1.0 + 2.0 * np.sin(2 * np.pi * t)
    np.testing.assert_allclose(exact["by_acceleration_torque"], 3.0 * accel, rtol=0, atol=1e-9)


def test_the_ledger_closes_with_the_sources_work_and_their_impulses(exact, filtered):
    for run in (exact, filtered):
        assert run.summary["energy_relative_residual"] < 1e-9
    # each source's work: the kinetic and strain energy it leaves (no loss in either scene)
    assert exact.energy_balance["by_acceleration_work"] == pytest.approx(
        0.5 * 3.0 * (exact["e_speed"][-1] ** 2 - 1.0), rel=1e-9)
    # the angle's: what it leaves in the far inertia and the spring, its shaft at rest at both ends (its jumps'
    # kinetic energy, 0 to 1 rad/s and back, given and taken again); to 4e-10 of the 12.5 J the spring starts with
    left = 0.5 * 1.0 * exact["d_speed"][-1] ** 2 + 50.0 * (exact["d_angle"][-1] - 1.5) ** 2 - 50.0 * 0.5**2
    assert exact.energy_balance["by_angle_work"] == pytest.approx(left, abs=1e-8)


def test_modelicas_filters_follow_the_reference_as_their_own_equations_do(filtered):
    run, t = filtered, filtered.time
    lag = t <= 1.0  # w' = (w_ref - w) w_c from the reference's start, 0: w = 10 (t - (1 - exp(-w_c t)) / w_c)
    crossover = 4 * np.pi
    np.testing.assert_allclose(run["a_speed"][lag], 10 * (t[lag] - (1 - np.exp(-crossover * t[lag])) / crossover),
                               rtol=0, atol=1e-10)

    def bessel(time, z):
        reference = np.interp(time, [0, 1, 2], [0.5, 1.5, 1.5])
        return [z[1], ((reference - z[0]) * crossover - 1.3617 * z[1]) * crossover / 0.6180]

    alone = solve_ivp(bessel, (0, 3), [0.5, 0.0], t_eval=t, method="DOP853", rtol=1e-12, atol=1e-13, max_step=1e-3)
    np.testing.assert_allclose(run["c_angle"], alone.y[0], rtol=0, atol=1e-9)
    np.testing.assert_allclose(run["c_speed"], alone.y[1], rtol=0, atol=1e-9)


def test_a_driven_shaft_drags_a_clutch_until_it_locks():
    """b (2 kg*m^2, against 1 N*m) is dragged by a clutch of 5 N*m sliding, 6 N*m holding, from a shaft driven at
    2 rad/s, then 4 rad/s from 0.5 s (a step the clutch cannot carry: it slips on): b = 2 t meets 4 rad/s at
    t = 2 s and locks; the heat 5 x (the slip's integral, 3 rad) = 15 J."""
    run = simulate(scenario_from_text(f"""name: dragged
drivetrain:
  shafts:
    a: {{inertia: 1 kg*m^2}}
    b: {{inertia: 2 kg*m^2}}
  torques:
    - {{shaft: b, torque: -1 N*m}}
  clutches:
    clutch: {{between: [a, b], static_friction: 0.6, kinetic_friction: 0.5, effective_radius: 1 m, force: 10 N}}
  motion_sources:
    drive: {{shaft: a, speed: [[0 s, 2 rad/s], [0.5 s, 2 rad/s], [0.5 s, 4 rad/s], [3 s, 4 rad/s]]}}
{SETTINGS}"""))
    t = run.time
    np.testing.assert_allclose(run["b_speed"][t <= 2.0], 2.0 * t[t <= 2.0], rtol=0, atol=1e-12)
    assert run.events["time"].tolist() == [pytest.approx(2.0, abs=1e-12)]
    assert run.energy_balance["clutch_energy"] == pytest.approx(15.0, rel=1e-9)
    assert run["drive_torque"][t < 2.0] == pytest.approx(5.0, abs=1e-9)
    assert run["drive_torque"][t > 2.0] == pytest.approx(1.0, abs=1e-9)
    assert run.summary["energy_relative_residual"] < 1e-12


@pytest.mark.parametrize("keys, key, says", [
    ({"angle": "1 rad"}, "angle", "give one motion"),
    ({"filter_frequency": "50 Hz", "speed": None, "acceleration": "1 rad/s^2"}, "filter_frequency", "exactly"),
    ({"shaft": "nowhere"}, "shaft", "no shaft 'nowhere'"),
])
def test_bad_motion_sources_are_refused_in_one_line(tmp_path, keys, key, says):
    path = tmp_path / "sources.yaml"
    path.write_text(EXACT)
    refused_in_one_line(path, part_keys_set("motion_sources", "by_speed", keys),
                        f"drivetrain.motion_sources.by_speed.{key}", says, tmp_path)


def test_a_shaft_driven_to_an_angle_may_not_start_elsewhere(tmp_path):
    path = tmp_path / "sources.yaml"
    path.write_text(EXACT)
    refused_in_one_line(path, part_keys_set("shafts", "c", {"angle": "0 rad"}), "drivetrain.shafts.c.angle",
                        "drives it from 0.5 rad", tmp_path)



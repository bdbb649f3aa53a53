"""A motor from its nameplate, and an induction motor by Kloss's formula, against closed forms.

- The nameplate's rated power and speed with the no-load speed: the line through the rated point, C0 = T_N / s_N;
  the run is the one given that stall torque, bit for bit.
- Kloss's T(s) = 2 T_b / (s / s_b + s_b / s): a rotor run up from rest reaches each speed at the time the
  closed form of J dw / dt = T(w) gives, t(s) = J w_s / (2 T_b s_b) ((1 - s^2) / 2 + s_b^2 ln(1 / s)).
- Its breakdown slip from the rated point: Kloss's curve through it, T(s_N) = P_N / n_N.
- Bad input: one line naming the key.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import EXERCISE6_FILE, drawn

from hoistsim import load_scenario, simulate
from hoistsim.errors import ScenarioError

SYNCHRONOUS = 1500 * math.pi / 30  # rad/s


def _rotor(duration="1 s", **motor):
    return drawn("motor", duration, "1 ms", shafts={"rotor": {"inertia": "0 kg*m^2"}},
                 motors={"motor": {"shaft": "rotor", "inertia": "0.5 kg*m^2", "no_load_speed": "1500 rpm", **motor}})


def test_the_nameplate_draws_the_line_through_the_rated_point():
    """15 kW at 280 rpm, 300 rpm at no load: T_N = 511.6 N*m at a slip of 1/15, so C0 = 15 T_N = 7673.5 N*m; exercise
    6 so written runs as with that stall torque."""
    nameplate = load_scenario(EXERCISE6_FILE, overrides={"motor.stall_torque": None, "motor.rated_power": "15 kW",
                                                         "motor.rated_speed": "280 rpm"})
    rated_torque = 15000.0 / (280 * math.pi / 30)
    assert nameplate.motor.stall_torque == pytest.approx(rated_torque * 15.0, rel=1e-12)
    given = load_scenario(EXERCISE6_FILE, overrides={"motor.stall_torque": f"{nameplate.motor.stall_torque!r} N*m"})
    ours, theirs = simulate(nameplate), simulate(given)
    assert np.array_equal(ours["motor_speed"], theirs["motor_speed"])
    assert ours.summary["slip_energy"] == theirs.summary["slip_energy"]


def test_an_induction_motor_runs_up_by_klosss_formula():
    """T_b 300 N*m at s_b 0.2, 1500 rpm synchronous, J 0.5 kg*m^2 from rest: each row's speed is reached at the
    closed form's time (to 1e-8 rad/s of speed: the time to 1e-8 / w', which grows without bound as the speed
    creeps up to the synchronous), the torque at each row is Kloss's, and the breakdown torque is the largest."""
    run = simulate(_rotor(breakdown_torque="300 N*m", breakdown_slip=0.2))
    tb, sb, j = 300.0, 0.2, 0.5
    slip = 1.0 - run["rotor_speed"] / SYNCHRONOUS
    running = slip < 1.0
    t = j * SYNCHRONOUS / (2 * tb * sb) * ((1 - slip[running] ** 2) / 2 + sb**2 * np.log(1 / slip[running]))
    acceleration = run["motor_torque"][running] / j
    np.testing.assert_allclose((t - run.time[running]) * acceleration, 0.0, rtol=0, atol=1e-8)
    np.testing.assert_allclose(run["motor_torque"], 2 * tb * sb * slip / (slip**2 + sb**2), rtol=1e-12, atol=1e-12)
    assert run["motor_torque"].max() == pytest.approx(tb, rel=1e-4)  # it passes s_b between two rows
    assert run.summary["energy_relative_residual"] < 1e-9


def test_the_breakdown_slip_follows_from_the_rated_point():
    """15 kW at 1440 rpm, T_b 2.5 T_N: s_N 0.04, s_b = s_N (k + sqrt(k^2 - 1)) = 0.19165; Kloss through the rated
    point gives T_N there."""
    scene = _rotor(breakdown_torque=f"{2.5 * 15000 / (1440 * math.pi / 30)!r} N*m", rated_power="15 kW",
                   rated_speed="1440 rpm")
    motor = scene.drivetrain.motors["motor"]
    rated_torque, rated_slip = 15000 / (1440 * math.pi / 30), 0.04
    assert motor.breakdown_slip == pytest.approx(rated_slip * (2.5 + math.sqrt(2.5**2 - 1)), rel=1e-12)
    s, sb = rated_slip, motor.breakdown_slip
    assert 2 * motor.breakdown_torque * sb * s / (s**2 + sb**2) == pytest.approx(rated_torque, rel=1e-12)


@pytest.mark.parametrize("motor, key, says", [
    ({"rated_power": "15 kW", "rated_speed": "1500 rpm"}, "rated_speed", "must be below no_load_speed"),
    ({"rated_power": "15 kW"}, "rated_speed", "required with a linear characteristic from the nameplate"),
    ({"rated_power": "15 kW", "rated_speed": "1440 rpm", "stall_torque": "300 N*m"}, "stall_torque",
     "not both"),
    ({"breakdown_torque": "300 N*m"}, "breakdown_slip", "required with breakdown_torque"),
    ({"breakdown_slip": 0.2}, "breakdown_torque", "required with breakdown_slip"),
    ({"breakdown_torque": "300 N*m", "breakdown_slip": 1.5}, "breakdown_slip", "at most 1"),
    ({"breakdown_torque": "50 N*m", "rated_power": "15 kW", "rated_speed": "1440 rpm"}, "breakdown_torque",
     "must exceed the rated torque"),
    ({"breakdown_torque": "300 N*m", "breakdown_slip": 0.2, "rated_power": "15 kW", "rated_speed": "1440 rpm"},
     "breakdown_slip", "not both"),
    ({"breakdown_torque": "300 N*m", "breakdown_slip": 0.2, "stall_torque": "300 N*m"}, "stall_torque",
     "give one characteristic"),
    ({"breakdown_torque": "250 N*m", "rated_power": "15 kW", "rated_speed": "1000 rpm"}, "breakdown_torque",
     "beyond standstill"),
])
def test_a_bad_nameplate_is_one_line_naming_its_key(motor, key, says):
    with pytest.raises(ScenarioError) as err:
        _rotor(**motor)
    assert err.value.key == f"drivetrain.motors.motor.{key}" and says in err.value.message, (err.value.key,
                                                                                              err.value.message)


def test_check_prints_the_characteristic_the_nameplate_makes():
    """`hoistsim check` works the nameplate out: the stall torque of the line through the rated point, or Kloss's
    torque at standstill, 2 T_b s_b / (1 + s_b^2), its breakdown torque and the speed it gives it at."""
    from hoistsim.studies.machine_tables import machine_table

    linear = load_scenario(EXERCISE6_FILE, overrides={"motor.stall_torque": None, "motor.rated_power": "15 kW",
                                                      "motor.rated_speed": "280 rpm"})
    text = machine_table(linear)
    assert "motor's torque at standstill" in text and "7674" in text  # 15 T_N, T_N = 15 kW / 280 rpm
    kloss = load_scenario(EXERCISE6_FILE, overrides={"motor.stall_torque": None, "motor.breakdown_torque": "1300 N*m",
                                                     "motor.breakdown_slip": 0.25})
    text = machine_table(kloss)
    standstill = 2 * 1300 * 0.25 / (1 + 0.25**2)
    assert f"{standstill:.4g}" in text and "breakdown torque, at 225 rpm (slip 0.25)" in text

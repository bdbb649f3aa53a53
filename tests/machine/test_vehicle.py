"""Links between shafts and masses (a gear stage with a radius: a pinion and its rack, a wheel rolling on the line;
a gear stage between two masses) and a vehicle's driving resistances (drivetrain.vehicles): Modelica's
IdealGearR2T, IdealRollingWheel and Vehicle.

- Vehicle (scenarios/modelica/translational/) within 1e-3 of each comparison signal's range at every reference
  row, the trailer joined to vehicle1 by a gear of ratio 1 between the two masses; the ledger closes.
- Closed forms: a pinion's torque accelerating its rack (the mass reaching the shaft as m r^2); a vehicle coasting
  to rest against its rolling resistance (constant, then linear below its regularization speed: an exponential),
  against the air's drag alone (v0 / (1 + c v0 t / m)), and driven up a grade.
- Bad input: a radius between two shafts, a shaft geared to a mass without a radius, a lossy stage on a mass, a
  mass's velocity that disagrees with its pinion's speed, a vehicle on no mass: one line naming the key.
- New values (a radius, the resistances' coefficients, the grade) compile nothing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import SCENARIOS, part_keys_set, refused_in_one_line
from modelica_reference import deviations, signals

from hoistsim import load_scenario, scenario_from_dict, simulate

FOLDER = SCENARIOS / "modelica" / "translational"
G = 9.80665


def test_vehicle_against_dymolas_published_trajectories():
    """Three vehicles of 100 kg on wheels, one pulling a trailer, driven by torque tables over 60 s, a grade from 20
    s to 25 s: each signal within 1e-3 of its range (measured: 1.2e-5, the velocities); the ledger closes (6e-13)."""
    run = simulate(load_scenario(FOLDER / "Vehicle.yaml"))
    worst = deviations(run, "translational/Vehicle", signals("translational/Vehicle", run))
    assert max(worst.values()) < 1e-3, worst
    assert (run["trailer_position"] == run["vehicle1_position"]).all()
    assert run.summary["energy_relative_residual"] < 1e-10


def _cart(inertia=0.5, mass=200.0, radius=0.2, torque=0.0, velocity=None, rolling=0.0, drag=0.0, inclination=0.0,
          duration=10.0, overrides=()):
    """A cart on a wheel (a shaft of ``inertia`` and a gear stage of ``radius``) driven by a torque, with its
    driving resistances: one program for every value."""
    cart = {"mass": f"{mass} kg"} | ({} if velocity is None else {"velocity": f"{velocity} m/s"})
    return {"name": "cart", "gravity": f"{G} m/s^2", "drivetrain": {
        "shafts": {"wheel": {"inertia": f"{inertia} kg*m^2"}}, "masses": {"cart": cart},
        "gears": {"rolling": {"between": ["wheel", "cart"], "radius": f"{radius} m"}},
        "torques": [{"shaft": "wheel", "torque": f"{torque} N*m"}],
        "vehicles": {"cart": {"mass": "cart", "rolling_resistance": rolling,
                              "drag": {"coefficient": drag, "area": "2 m^2", "air_density": "1.2 kg/m^3"},
                              "inclination": [["0 s", inclination], ["20 s", inclination]]}}},
        "simulation": {"duration": f"{duration} s", "output_interval": "10 ms", "rtol": 1e-11, "atol": 1e-13}}


def test_a_pinion_drives_its_rack_up_a_grade_as_its_closed_form():
    """A torque T on a pinion of inertia J and radius r driving a mass m up a grade i: (J / r^2 + m) a = T / r - m g
    sin(atan i), from rest; its position a t^2 / 2, its wheel's speed v / r, the grade's work -m g sin(alpha) s."""
    J, m, r, T, i = 0.5, 200.0, 0.2, 150.0, 0.1
    run = simulate(scenario_from_dict(_cart(inertia=J, mass=m, radius=r, torque=T, inclination=i)))
    a = (T / r - m * G * math.sin(math.atan(i))) / (J / r**2 + m)
    t = run.time
    np.testing.assert_allclose(run["cart_velocity"], a * t, rtol=0, atol=1e-10)
    np.testing.assert_allclose(run["cart_position"], 0.5 * a * t**2, rtol=0, atol=1e-9)
    np.testing.assert_allclose(run["wheel_speed"], a * t / r, rtol=0, atol=1e-9)
    assert run.energy_balance["cart_grade_work"] == pytest.approx(-m * G * math.sin(math.atan(i)) * 0.5 * a * 100,
                                                                    rel=1e-10)
    assert run.summary["energy_relative_residual"] < 1e-10


def test_a_vehicle_coasts_to_rest_against_its_rolling_resistance_as_its_closed_form():
    """200 kg at 2 m/s, Cr 0.02: it slows at Cr g (the wheel's inertia J / r^2 added to the mass) until 1 mm/s, then
    exponentially, at the rate Cr g / (1 mm/s), to rest."""
    J, m, r, cr, v0, v_reg = 0.5, 200.0, 0.2, 0.02, 2.0, 1e-3
    run = simulate(scenario_from_dict(_cart(inertia=J, mass=m, radius=r, velocity=v0, rolling=cr)))
    effective = m + J / r**2
    slowing = cr * m * G / effective
    t1 = (v0 - v_reg) / slowing
    t = run.time
    expected = np.where(t < t1, v0 - slowing * t, v_reg * np.exp(-slowing / v_reg * np.maximum(t - t1, 0.0)))
    np.testing.assert_allclose(run["cart_velocity"], expected, rtol=0, atol=1e-9)
    assert run["wheel_speed"][0] == pytest.approx(v0 / r, rel=1e-15)  # the wheel's speed from the mass's
    assert run.energy_balance["cart_rolling_loss"] == pytest.approx(0.5 * effective * (v0**2 - expected[-1] ** 2),
                                                                     rel=1e-9)


def test_a_vehicle_coasts_against_the_airs_drag_as_its_closed_form():
    """200 kg at 10 m/s against Cd A rho / 2 v^2 alone (0.4, 2 m^2, 1.2 kg/m^3): v = v0 / (1 + c v0 t / M), M the
    mass with its wheel's J / r^2."""
    J, m, r, v0 = 0.5, 200.0, 0.2, 10.0
    run = simulate(scenario_from_dict(_cart(inertia=J, mass=m, radius=r, velocity=v0, drag=0.4)))
    c, effective = 0.4 * 2.0 * 1.2 / 2.0, m + J / r**2
    np.testing.assert_allclose(run["cart_velocity"], v0 / (1.0 + c * v0 * run.time / effective), rtol=0, atol=1e-10)


@pytest.mark.parametrize("change, key, says", [
    (part_keys_set("gears", "rolling", {"between": ["wheel", "wheel1"]}), "drivetrain.gears.rolling.radius",
     "give between [shaft, mass]"),
    (part_keys_set("gears", "rolling", {"radius": None, "ratio": 4}), "drivetrain.gears.rolling.between",
     "joins a shaft to a mass"),
    (part_keys_set("gears", "hitch", {"efficiency": 0.9}), "drivetrain.gears.hitch.efficiency",
     "a stage that joins a mass is ideal"),
    (lambda d: d["drivetrain"]["masses"]["vehicle"].update({"velocity": "1 m/s"})
     or d["drivetrain"]["shafts"]["wheel"].update({"speed": "1 rad/s"}), "drivetrain.masses.vehicle.velocity",
     "must be 0.25 m/s"),
    (part_keys_set("vehicles", "trailer", {"mass": "nowhere"}), "drivetrain.vehicles.trailer.mass",
     "no mass 'nowhere'"),
])
def test_bad_links_and_vehicles_are_refused_in_one_line(change, key, says, tmp_path):
    refused_in_one_line(FOLDER / "Vehicle.yaml", change, key, says, tmp_path)


def test_new_values_of_links_and_resistances_compile_nothing():
    """A radius, the rolling and drag coefficients, the grade and the mass: the program the cart already compiled."""
    from hoistsim.machine.core import loop

    simulate(scenario_from_dict(_cart(velocity=2.0, rolling=0.02)))
    traced = loop.trace_count
    run = simulate(scenario_from_dict(_cart(mass=300.0, radius=0.3, velocity=3.0, rolling=0.01, drag=0.3,
                                            inclination=0.05, torque=10.0)))
    assert run["cart_velocity"][0] == 3.0 and loop.trace_count == traced

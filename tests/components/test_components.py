"""Machine elements from geometry and the reduction to the two clutch shafts (exercise 6)."""

from __future__ import annotations

import math

import pytest
from helpers import SCENARIOS, scene

from hoistsim import load_scenario
from hoistsim.components import ConeClutch
from hoistsim.references.model import Machine


def test_exercise6_reduced_model():
    machine = Machine.from_scenario(load_scenario(SCENARIOS / "exercise6_direct_start.yaml"))
    d = machine.reduced()
    tau = 90 / 17
    assert machine.motor.inertia == pytest.approx(0.9)  # 40 kg x (0.15 m)^2
    assert machine.gears.pinion_pitch_radius == pytest.approx(0.034)
    assert machine.gears.wheel_pitch_radius == pytest.approx(0.180)
    assert d.ratio == pytest.approx(tau)
    assert d.output_inertia == pytest.approx((40 + 500 * 0.2**2) / tau**2)  # (I + M R^2)/tau^2
    assert d.load_torque == pytest.approx(500 * 9.81 * 0.2 / tau)  # 185.3 N*m
    assert d.clutch_constant == pytest.approx(0.22 / math.sin(math.radians(25)))


def test_equal_kinetic_energy_and_power():
    """The reduction keeps kinetic energy and the load's power, whatever the speed."""
    machine = Machine.from_scenario(scene(mass="730 kg"))
    d = machine.reduced()
    pinion = 17.3  # rad/s
    drum = pinion / machine.gears.ratio
    rope = drum * machine.drum.rope_radius
    energy = 0.5 * machine.drum.inertia * drum**2 + 0.5 * machine.load.mass * rope**2
    assert 0.5 * d.output_inertia * pinion**2 == pytest.approx(energy)
    assert d.load_torque * pinion == pytest.approx(machine.load.weight * rope)


def test_uniform_pressure_radius_is_the_annulus_centroid():
    wear = ConeClutch(0.20, 0.24, math.radians(25), 0.3, 0.1)
    pressure = ConeClutch(0.20, 0.24, math.radians(25), 0.3, 0.1, mean_radius_rule="uniform_pressure")
    assert wear.mean_radius == pytest.approx(0.22)
    assert pressure.mean_radius == pytest.approx(2 / 3 * (0.24**3 - 0.20**3) / (0.24**2 - 0.20**2))
    assert pressure.mean_radius > wear.mean_radius  # a new clutch carries a little more
    assert wear.force_for_torque(wear.static_capacity(2000.0)) == pytest.approx(2000.0)


def test_extra_inertias_are_reduced_to_their_shafts():
    base = Machine.from_scenario(scene()).reduced()
    data = scene().raw
    data["clutch"]["driving_inertia"] = "0.1 kg*m^2"
    data["clutch"]["driven_inertia"] = "0.05 kg*m^2"
    data["gears"]["pinion_inertia"] = "0.01 kg*m^2"
    data["gears"]["wheel_inertia"] = "2 kg*m^2"
    from hoistsim import scenario_from_dict

    d = Machine.from_scenario(scenario_from_dict(data)).reduced()
    assert d.motor_inertia == pytest.approx(base.motor_inertia + 0.1)
    assert d.output_inertia == pytest.approx(base.output_inertia + 0.05 + 0.01 + 2 / (90 / 17) ** 2)

"""Scenes for tests: the exercise-6 hoist with chosen loads, forces, speeds and brake."""

from __future__ import annotations

import copy

from hoistsim import scenario_from_dict

EXERCISE6 = {
    "name": "test-scene",
    "motor": {"stall_torque": "500 N*m", "no_load_speed": "300 rpm", "inertia": "0.9 kg*m^2"},
    "clutch": {
        "inner_radius": "20 cm", "outer_radius": "24 cm", "half_angle": "25 deg",
        "static_friction": 0.3, "kinetic_friction": 0.1, "engagement_force": "3201 N",
    },
    "gears": {"pinion_teeth": 17, "wheel_teeth": 90, "module": "4 mm", "pressure_angle": "20 deg"},
    "drum": {"diameter": "40 cm", "inertia": "40 kg*m^2"},
    "load": {"mass": "500 kg"},
    "simulation": {"duration": "2 s", "output_interval": "5 ms", "rtol": 1e-10, "atol": 1e-12},
}


def scene(force="3201 N", mass="500 kg", motor_speed=None, brake=None, duration="2 s", name="test-scene",
          **simulation):
    """A validated scenario; ``force`` is anything the engagement_force key accepts."""
    data = copy.deepcopy(EXERCISE6)
    data["name"] = name
    data["clutch"]["engagement_force"] = force
    data["load"]["mass"] = mass
    data["simulation"]["duration"] = duration
    data["simulation"].update(simulation)
    if motor_speed is not None:
        data["initial"] = {"motor_speed": motor_speed}
    if brake is not None:
        data["brake"] = {"release_time": brake}
    return scenario_from_dict(data, name=name)


def reduced(run):
    """The two-shaft reduced model of a run's scenario (:mod:`hoistsim.references.model`): the oracles' numbers."""
    from hoistsim.references.model import Machine

    return Machine.from_scenario(run.scenario).reduced()

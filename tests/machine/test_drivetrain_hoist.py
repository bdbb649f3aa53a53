"""The hoist drawn as a drivetrain is the hoist: the same numbers as its own sections.

Exercise 6 written as shafts (motor, pinion, drum), a motor named after its shaft, the cone clutch as a
friction clutch whose effective radius comes from its cone, a gear stage of ratio 90/17 and the load on
the drum's rope; the brake-start scene adds its brake as a clutch to the ground whose force steps to
zero at the release.  Same bodies, same laws: every shared column equal to 1e-12 of its range.
"""

from __future__ import annotations

import copy

import numpy as np
import pytest
from helpers import EXERCISE6

from hoistsim import load_scenario, scenario_from_dict, simulate

# the hoist's column -> the drawn drivetrain's (named after its parts: shaft motor, clutch clutch...)
SHARED = {"motor_speed": "motor_speed", "drum_speed": "drum_speed", "clutch_torque": "clutch_torque",
          "slip_speed": "clutch_slip", "clutch_locked": "clutch_locked", "load_position": "load_position",
          "load_velocity": "load_velocity", "motor_torque": "motor_torque", "motor_work": "motor_work"}


def drawn(hoist: dict) -> dict:
    """The drivetrain form of a hoist scene given as a dict of its sections."""
    motor, clutch, gears = hoist["motor"], hoist["clutch"], hoist["gears"]
    cone = {key: clutch[key] for key in ("inner_radius", "outer_radius", "half_angle")}
    return {"name": "drawn-hoist", "drivetrain": {
        "shafts": {"motor": {"inertia": "0 kg*m^2"}, "pinion": {"inertia": "0 kg*m^2"},
                   "drum": {"inertia": hoist["drum"]["inertia"]}},
        "motors": {"motor": {"shaft": "motor", **{k: v for k, v in motor.items()}}},
        "clutches": {"clutch": {"between": ["motor", "pinion"], "static_friction": clutch["static_friction"],
                                "kinetic_friction": clutch["kinetic_friction"], "cone": cone,
                                "force": clutch["engagement_force"]}},
        "gears": {"stage": {"between": ["pinion", "drum"], "ratio": gears["wheel_teeth"] / gears["pinion_teeth"]}},
        "load": {"shaft": "drum", "rope_radius": "20 cm", "mass": hoist["load"]["mass"]}},
        "simulation": hoist["simulation"]}


def assert_same(hoist_run, drawn_run, columns=SHARED, names=None):
    """``names``: the hoist's part -> the drawn drivetrain's, where an event names one they call otherwise."""
    for column, drawn_column in columns.items():
        expected, got = hoist_run[column], drawn_run[drawn_column]
        scale = max(np.abs(expected).max(), 1e-300)
        assert np.abs(got - expected).max() <= 1e-12 * scale, column
    # the hoist's brake_release (a scheduled event) is the drawn brake's disengage, there too
    kept = [run.events["kind"] != "brake_release" for run in (hoist_run, drawn_run)]
    for field in ("time", "kind", "element", "mode_after"):
        expected = hoist_run.events[field][kept[0]]
        if field == "element" and names:
            expected = np.asarray([names.get(name, name) for name in expected], dtype=object)
        assert np.array_equal(expected, drawn_run.events[field][kept[1]]), field
    assert drawn_run.summary["energy_relative_residual"] < 1e-9


@pytest.mark.parametrize("force", ["3201 N", [["0 s", "0 N"], ["0.5 s", "0 N"], ["0.6 s", "2000 N"]]],
                         ids=["direct start", "clutch ramped on"])
def test_exercise6_drawn_as_a_drivetrain_is_the_hoist(force):
    hoist = copy.deepcopy(EXERCISE6)
    hoist["clutch"]["engagement_force"] = force
    assert_same(simulate(scenario_from_dict(hoist)), simulate(scenario_from_dict(drawn(hoist))))


@pytest.mark.slow
def test_the_brake_start_drawn_as_a_drivetrain_is_the_hoist():
    scenario = load_scenario("scenarios/start_against_a_slipping_brake.yaml")
    hoist = {"motor": {"stall_torque": "500 N*m", "no_load_speed": "300 rpm", "inertia": "0.9 kg*m^2"},
             "clutch": {"inner_radius": "20 cm", "outer_radius": "24 cm", "half_angle": "25 deg",
                        "static_friction": 0.3, "kinetic_friction": 0.1,
                        "engagement_force": [["0 s", "0 N"], ["0.5 s", "0 N"], ["0.6 s", "9000 N"]]},
             "gears": {"pinion_teeth": 17, "wheel_teeth": 90}, "drum": {"inertia": "40 kg*m^2"},
             "load": {"mass": "500 kg"},
             "simulation": {"duration": "3 s", "output_interval": "1 ms", "rtol": 1e-8, "atol": 1e-10}}
    data = drawn(hoist)
    # the brake: holds 1000 N*m, slips at 900, released at 0.8 s (a force of 1000 N on a 1 m radius)
    data["drivetrain"]["clutches"]["brake"] = {
        "between": ["drum", "ground"], "static_friction": 1.0, "kinetic_friction": 0.9,
        "effective_radius": "1 m", "force": [["0 s", "1000 N"], ["0.8 s", "1000 N"], ["0.8 s", "0 N"]]}
    hoist_run, drawn_run = simulate(scenario), simulate(scenario_from_dict(data))
    assert_same(hoist_run, drawn_run)
    np.testing.assert_allclose(drawn_run["brake_torque"], -hoist_run["brake_torque"], rtol=0, atol=1e-12 * 1000)


def test_a_lossy_stage_drawn_is_the_hoists_lossy_mesh():
    # the load runs back through the mesh (the wheel drives, eta_b) until the clutch engages and lifts it (the
    # pinion drives, eta): both laws of the losses, and the switch between them (pressed hard enough to lift it
    # within the run: before, the pinion drives only where the teeth carry nothing but round-off)
    hoist = copy.deepcopy(EXERCISE6)
    hoist["clutch"]["engagement_force"] = [["0 s", "0 N"], ["0.3 s", "0 N"], ["0.4 s", "6000 N"]]
    hoist["gears"].update(efficiency=0.9, backdrive_efficiency=0.8)
    hoist["simulation"]["duration"] = "1.5 s"
    data = drawn(hoist)
    data["drivetrain"]["gears"]["stage"].update(efficiency=0.9, backdrive_efficiency=0.8)
    hoist_run, drawn_run = simulate(scenario_from_dict(hoist)), simulate(scenario_from_dict(data))
    assert set(np.unique(hoist_run["mesh_mode"])) >= {1, 2}
    assert_same(hoist_run, drawn_run, SHARED | {"mesh_torque": "stage_mesh_torque", "mesh_mode": "stage_mesh_mode",
                                                "mesh_heat": "stage_mesh_heat", "mesh_loss_power": "stage_mesh_loss_power"},
                names={"mesh": "stage"})
    assert drawn_run.summary["stage_mesh_loss_energy"] == pytest.approx(hoist_run.summary["mesh_loss_energy"],
                                                                       rel=1e-12)

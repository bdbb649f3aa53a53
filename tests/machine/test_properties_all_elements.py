"""Properties over random scenes with every friction element at once (hypothesis).

Clutch, friction brake, ratchet and lossy mesh together, each switching on
its own: at every output row each obeys its friction law, and the energy
balance closes to 1e-8 at rtol 1e-10.
"""

from __future__ import annotations

import copy
import os

import numpy as np
import pytest
from helpers import EXERCISE6, engagement_forces, property_settings, reduced
from hypothesis import example, given
from hypothesis import strategies as st

from hoistsim import scenario_from_dict, simulate
from hoistsim.references.model import STICK_TOLERANCE

# The same scenes every run (a check that passes or fails by the code alone); HOISTSIM_PROPERTY_SEARCH=1 draws
# new ones, to search.
SETTINGS = property_settings(40, derandomize=not os.environ.get("HOISTSIM_PROPERTY_SEARCH"))


def build(force, mass, motor_rpm, drum_rpm, brake, ratchet_release, efficiency, backdrive):
    data = copy.deepcopy(EXERCISE6)
    data["clutch"]["engagement_force"] = force
    data["load"]["mass"] = f"{mass} kg"
    data["initial"] = {"motor_speed": f"{motor_rpm} rpm", "drum_speed": f"{drum_rpm} rpm"}
    release, static, kinetic_share, apply_after = brake
    data["brake"] = {"release_time": f"{release} s", "static_torque": f"{static} N*m",
                     "kinetic_torque": f"{static * kinetic_share} N*m"}
    if apply_after is not None:
        data["brake"]["apply_time"] = f"{release + apply_after} s"
    data["ratchet"] = {} if ratchet_release is None else {"release_time": f"{ratchet_release} s"}
    data["gears"].update(efficiency=efficiency, backdrive_efficiency=backdrive)
    data["simulation"].update(duration="1.2 s", output_interval="5 ms", rtol=1e-10, atol=1e-12)
    return scenario_from_dict(data)


brakes = st.tuples(st.floats(0.0, 0.6), st.floats(100.0, 3000.0), st.floats(0.2, 1.0),
                   st.one_of(st.none(), st.floats(0.05, 0.5)))
# No load, or one of a gram or more: a load of ~1e-200 kg or less is a case of its own
# (test_a_load_of_nothing_but_round_off_through_a_lossy_mesh), not a random draw's to find again.
masses = st.one_of(st.just(0.0), st.floats(1e-3, 900.0))
scenes = st.builds(build, engagement_forces, masses, st.floats(0.0, 400.0), st.floats(0.0, 30.0),
                   brakes, st.one_of(st.none(), st.floats(0.0, 1.0)), st.floats(0.5, 1.0), st.floats(0.3, 1.0))


@pytest.mark.slow
@SETTINGS
@given(scenes)
# At rest, the brake released at once, the pawl in and a mesh of efficiency 0.5: the clutch's capacity
# near the motor's stall torque, which lifts the load through the mesh only just, or only just not (the
# mesh and the pawl share the drum's hold).  The static check once let go in turn and stuck a coupling
# beyond its capacity here.
@example(build("2717.0 N", 620.0, 0.0, 0.0, (0.0, 100.0, 1.0, None), None, 0.5, 1.0))
@example(build("2765.0 N", 675.0, 0.0, 0.0, (0.0, 100.0, 1.0, None), None, 0.5, 1.0))
@example(build("3202.0 N", 675.0, 3.6e-85, 0.0, (0.0, 100.0, 1.0, None), None, 0.5, 1.0))
# No load, the pinion a shade faster than the motor, the pawl clicking and a mesh of efficiency 0.5: where
# the clutch's sides meet the tooth load turns, and holding them together takes more than the clutch's
# capacity once the mesh's losses answer it, so it slips on forwards.  The check of a clutch let go once
# moved its parting along one column of the response, which leaves the mesh's answer out: it found the
# clutch could hold, no way was consistent, and the clutch was held beyond its capacity for 40 ms.
@example(build("989.0 N", 0.0, 157.0, 30.0, (0.0, 100.0, 1.0, None), None, 0.5, 1.0))
def test_every_friction_element_obeys_its_law_at_every_row(s):
    run = simulate(s)
    tiny = 1e-9
    # the clutch
    d = reduced(run)
    torque, force, mode = run["clutch_torque"], run["engagement_force"], run["clutch_mode"]
    assert np.all(np.abs(torque[mode == 0]) <= d.static_capacity(force[mode == 0]) * (1 + STICK_TOLERANCE) + tiny)
    np.testing.assert_allclose(torque[mode == 1], d.kinetic_torque(force[mode == 1]), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(torque[mode == 2], -d.kinetic_torque(force[mode == 2]), rtol=1e-12, atol=1e-12)
    assert np.all(torque[mode == 3] == 0.0)
    # the brake: held within its static torque, slipping at its kinetic torque against the drum's motion
    brake, mode = run["brake_torque"], run["brake_mode"]
    static, kinetic = s.brake.static_torque, s.brake.kinetic_torque
    assert np.all(np.abs(brake[mode == 0]) <= static * (1 + STICK_TOLERANCE) + tiny)
    np.testing.assert_allclose(brake[mode == 1], -kinetic, rtol=1e-12)
    np.testing.assert_allclose(brake[mode == 2], kinetic, rtol=1e-12)
    assert np.all(brake[mode == 3] == 0.0)
    assert np.all(run["drum_speed"][mode == 1] >= -tiny) and np.all(run["drum_speed"][mode == 2] <= tiny)
    # the pawl: holds the load up, never down; until it is lifted the drum never turns to lower
    pawl, engaged = run["ratchet_torque"], run["ratchet_engaged"] == 1
    assert np.all(pawl[engaged] >= -tiny) and np.all(pawl[~engaged] == 0.0)
    lifted = s.ratchet.release_time if s.ratchet.release_time is not None else np.inf
    assert np.all(run["drum_speed"][run.time < lifted] >= -tiny)
    # the mesh: still when held, losing (1/eta - 1) or (1 - eta_b) of the power through its teeth
    mesh, through = run["mesh_mode"], np.abs(run["mesh_torque"] * run["drum_speed"])
    assert np.all(run["drum_speed"][mesh == 0] == 0.0) and np.all(run["mesh_loss_power"][mesh == 0] == 0.0)
    eta, eta_b = s.gears.efficiency, s.gears.backdrive_efficiency
    scale = 1e-9 * max(through.max(), 1.0)
    np.testing.assert_allclose(run["mesh_loss_power"][mesh == 1], (1 / eta - 1) * through[mesh == 1], rtol=1e-9,
                               atol=scale)
    np.testing.assert_allclose(run["mesh_loss_power"][mesh == 2], (1 - eta_b) * through[mesh == 2], rtol=1e-9,
                               atol=scale)
    assert run.energy_balance["relative_residual"] < 1e-8


@pytest.mark.slow
def test_a_load_of_nothing_but_round_off_through_a_lossy_mesh():
    """A load of 1.8e-249 kg through a lossy mesh: its tooth load, round-off about zero, reverses at t = 1.3e-251 s.
    Found by the property search above; the loop made no progress from there ("too many segments"; 1e-100 kg
    ran, 1e-200 kg did not) while each pass solved again for crossings found together could be solved again
    with ever shorter steps.  A pass is now solved again three times at most, and the run goes to its end."""
    scene = build([["0 s", "0 N"], ["0.5 s", "500.0 N"]], 1.8480171191224565e-249, 6.0, 1.0, (0.0, 100.0, 1.0, None),
                  None, 1.0, 1.0)
    run = simulate(scene)
    assert run.time[-1] == scene.simulation.duration
    assert run.energy_balance["relative_residual"] < 1e-8



# found by the random search: tsit5 stops at t = 0.0656 s in this one, and did at t = 0.1055 s in the next (which
# runs to its end since the tooth load's sum took the shafts parts declare on the drum, the same zeros in another
# order: the stop is one of round-off, not yet found)
STOPPING = ([["0 s", "0 N"], ["0.5 s", "3996.0 N"]], 0.0, 0.0, 1.0, (0.5, 101.0, 0.94140625, None), None,
            0.658203125, 1.0)
STOPPED = ([["0 s", "0 N"], ["0.25 s", "6804.0 N"]], 0.0, 0.0, 2.0, (0.0, 2984.0, 0.203125, 0.05), None, 0.765625,
           0.5)


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="known: the solver stops on too small a step (at 0.0656 s) in this scene "
                   "without a load, with a lossy mesh, a brake and no pawl; why is not yet found")
def test_a_scene_the_search_found_the_solver_stopping_on():
    simulate(build(*STOPPING))


@pytest.mark.slow
def test_a_scene_the_solver_stopped_on_runs_to_its_end():
    scene = build(*STOPPED)
    run = simulate(scene)
    assert run.time[-1] == scene.simulation.duration
    assert run.energy_balance["relative_residual"] < 1e-8

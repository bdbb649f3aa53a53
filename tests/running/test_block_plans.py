"""A summary-only sweep's plans built from a block's first run are the plans built run by run, leaf by leaf."""

from __future__ import annotations

import math

import jax
import numpy as np
import pytest
from helpers import SCENARIOS

from hoistsim import load_scenario, sweep
from hoistsim.machine.assemble import build_plan
from hoistsim.machine.elements import element_sections
from hoistsim.running import block_plans as bp
from hoistsim.scenario.sweep_runs import SweepRuns

FORCES = SCENARIOS / "force_sweep_engage_at_speed.yaml"
BRAKE = SCENARIOS / "engage_at_speed_with_brake.yaml"
WINDOW = SCENARIOS / "clutch_force_window.yaml"
COUPLED = SCENARIOS / "coupled_clutches.yaml"
STEADY = SCENARIOS / "exercise6_constant_speed.yaml"

SWEEPS = [
    (FORCES, ["clutch.engagement_force=3 kN:12 kN:7"]),
    (FORCES, ["load.mass=100 kg:900 kg:5", "clutch.engagement_force=4 kN,9 kN"]),
    (FORCES, ["drum.inertia=20 kg*m^2:60 kg*m^2:4"]),
    (FORCES, ["motor.stall_torque=400 N*m:600 N*m:4"]),
    (FORCES, ["motor.inertia=0.5 kg*m^2,1.2 kg*m^2"]),  # alternatives of rotor mass: the motor rebuilt
    (BRAKE, ["brake.release_time=0.55 s:0.9 s:4"]),
    # force tables of different lengths: padded, each row added one more boundary
    (BRAKE, ["clutch.engagement_force=[[[0 s, 0 N], [0.5 s, 0 N], [0.6 s, 5 kN]], 4 kN, "
             "[[0 s, 0 N], [0.3 s, 2 kN], [0.4 s, 2 kN], [0.6 s, 7 kN]]]"]),
    # a state's starting value: the starting state per run
    (WINDOW, ["clutch_heating.initial_temperature=20 degC:60 degC:3"]),
    (WINDOW, ["clutch_heating.max_temperature=70 degC,90 degC"]),
    # the start: each run's starting state its own
    (FORCES, ["initial.motor_speed=100 rpm:300 rpm:3"]),
    # a hoist started at its steady lift: each run's starting speeds its own
    (STEADY, ["load.mass=100 kg:400 kg:4"]),
    (STEADY, ["motor.stall_torque=500 N*m,600 N*m", "drum.inertia=20 kg*m^2,30 kg*m^2"]),
    # a drawn drivetrain's parts, by name and by a list's index
    (COUPLED, ["drivetrain.shafts.J1.inertia=0.5 kg*m^2:2 kg*m^2:4"]),
    (COUPLED, ["drivetrain.clutches.clutch2.kinetic_friction=0.3:0.5:3", "drivetrain.shafts.J4.speed=0 rad/s,1 rad/s"]),
    (COUPLED, ["drivetrain.torques.0.torque=[{harmonics: [{amplitude: 5 N*m, frequency: 5 Hz}]}, 4 N*m]"]),
]


@pytest.mark.parametrize("path, spec", SWEEPS, ids=[s[0] for _, s in SWEEPS])
def test_every_run_is_its_plan_built_alone(path, spec):
    runs = SweepRuns(load_scenario(path, sweeps=spec))
    plans = bp.block_plans(runs, list(range(len(runs))))
    assert plans is not None
    for i in range(len(runs)):
        alone, _ = build_plan(runs.scenario(i), summary_only=True)
        assert bp.same_plan(alone, plans.plan(i)), runs.label(i)


@pytest.mark.parametrize("path, spec, rebuilt", [
    (WINDOW, "clutch.engagement_force=4 kN:6 kN:3", {"clutch"}),
    # the clutch holds the heating section, but builds nothing from its heat capacity
    (WINDOW, "clutch_heating.heat_capacity=30 J/K:50 J/K:3", {"clutch_heating"}),
    # the heating's friction tables are the clutch's to use: the clutch alone is reached
    (WINDOW, "clutch_heating.static_friction=[[[20 degC, 0.3], [300 degC, 0.2]], [[20 degC, 0.3], [300 degC, 0.25]]]",
     {"clutch"}),
    # the drum's starting speed reaches the shafts that start at it (a rigid load's element keeps none)
    (FORCES, "initial.drum_speed=0 rpm,5 rpm", {"gears"}),
    (COUPLED, "drivetrain.shafts.J2.inertia=1 kg*m^2,2 kg*m^2", {"drivetrain.shafts.J2"}),
])
def test_only_the_elements_a_swept_key_reaches_are_built_per_run(path, spec, rebuilt):
    runs = SweepRuns(load_scenario(path, sweeps=[spec]))
    indices = list(range(len(runs)))
    plans = bp.block_plans(runs, indices)
    sections = [section for section, _, _ in element_sections(runs.scenario(0))]
    assert {sections[k] for k in plans.rebuilt} == rebuilt
    for i in indices:
        assert bp.same_plan(build_plan(runs.scenario(i), summary_only=True)[0], plans.plan(i)), runs.label(i)


def test_a_sweep_of_the_simulation_is_built_run_by_run():
    runs = SweepRuns(load_scenario(FORCES, sweeps=["simulation.rtol=1e-6,1e-8"]))
    assert bp.block_plans(runs, [0, 1]) is None


def test_a_missed_dependency_is_caught_and_the_block_built_run_by_run(monkeypatch):
    monkeypatch.setattr(bp, "reached_positions", lambda elements, changed: set())
    runs = SweepRuns(load_scenario(FORCES, sweeps=["clutch.engagement_force=3 kN:12 kN:5"]))
    assert bp.block_plans(runs, list(range(5))) is None


def test_the_summaries_are_those_of_plans_built_run_by_run(monkeypatch):
    s = load_scenario(BRAKE, sweeps=["clutch.engagement_force=[[[0 s, 0 N], [0.5 s, 0 N], [0.6 s, 5 kN]], "
                                     "3 kN, 7 kN, [[0 s, 0 N], [0.3 s, 2 kN], [0.4 s, 2 kN], [0.6 s, 7 kN]]]"])
    fast = sweep(s, summary_only=True, chunk_size=4).summary
    monkeypatch.setattr("hoistsim.running.blocks.block_plans", lambda runs, indices, **_: None)
    slow = sweep(s, summary_only=True, chunk_size=4).summary
    for key, values in fast.items():
        for a, b in zip(values, slow[key]):
            assert a == b or (isinstance(a, float) and math.isnan(a) and math.isnan(b)), key


@pytest.mark.parametrize("path, spec, stacked", [
    (FORCES, ["clutch.engagement_force=3 kN:12 kN:7"], True),
    (FORCES, ["load.mass=100 kg:900 kg:5", "clutch.engagement_force=4 kN,9 kN"], True),
    (BRAKE, ["brake.release_time=0.55 s:0.9 s:4"], True),
    # tables of different lengths do not stack
    (BRAKE, ["clutch.engagement_force=[[[0 s, 0 N], [0.6 s, 5 kN]], 4 kN]"], False),
    (WINDOW, ["clutch_heating.heat_capacity=30 J/K:50 J/K:3"], True),
    (COUPLED, ["drivetrain.shafts.J1.inertia=0.5 kg*m^2:2 kg*m^2:4"], True),
    (COUPLED, ["drivetrain.clutches.clutch2.kinetic_friction=0.3:0.5:3", "drivetrain.shafts.J4.speed=0 rad/s,1 rad/s"],
     True),
])
def test_a_swept_number_builds_its_element_once_for_the_block(path, spec, stacked):
    """Swept values that stack (numbers, tables of one length) build each reached element once, for all the
    block's runs; the plans are still every run's own, leaf by leaf."""
    runs = SweepRuns(load_scenario(path, sweeps=spec))
    plans = bp.block_plans(runs, list(range(len(runs))))
    kinds = {type(column) for column in plans.rebuilt.values()}
    assert kinds == ({bp.StackedElements} if stacked else {bp.ListedElements})
    for i in range(len(runs)):
        assert bp.same_plan(build_plan(runs.scenario(i), summary_only=True)[0], plans.plan(i)), runs.label(i)
    lanes = list(range(len(runs)))[::-1]
    chunk = plans.stacked(lanes)
    for lane, r in enumerate(lanes):
        one = jax.tree.map(lambda leaf: leaf[lane], chunk)
        assert bp.same_plan(build_plan(runs.scenario(r), summary_only=True)[0], one), runs.label(r)


def test_labels_of_many_runs_are_each_runs_label():
    runs = SweepRuns(load_scenario(FORCES, sweeps=["load.mass=100 kg:900 kg:3", "clutch.engagement_force=4 kN,9 kN"]))
    rows = np.array([5, 0, 3])
    assert list(runs.labels_of(rows)) == [runs.label(i) for i in rows]

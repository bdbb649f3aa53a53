"""A summary-only sweep's plans built from a block's first run are the plans built run by run, leaf by leaf."""

from __future__ import annotations

import math

import jax
import numpy as np
import pytest
from helpers import SCENARIOS

from hoistsim import load_scenario, sweep
from hoistsim.machine.assemble import build_plan
from hoistsim.running import block_plans as bp
from hoistsim.scenario.sweep_runs import SweepRuns

FORCES = SCENARIOS / "force_sweep_engage_at_speed.yaml"
BRAKE = SCENARIOS / "engage_at_speed_with_brake.yaml"
WINDOW = SCENARIOS / "clutch_force_window.yaml"

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
]


@pytest.mark.parametrize("path, spec", SWEEPS, ids=[s[0] for _, s in SWEEPS])
def test_every_run_is_its_plan_built_alone(path, spec):
    runs = SweepRuns(load_scenario(path, sweeps=spec))
    plans = bp.block_plans(runs, list(range(len(runs))))
    assert plans is not None
    for i in range(len(runs)):
        alone, _ = build_plan(runs.scenario(i), summary_only=True)
        assert bp.same_plan(alone, plans.plan(i)), runs.label(i)


@pytest.mark.parametrize("spec, rebuilt", [
    ("clutch.engagement_force=4 kN:6 kN:3", {"clutch"}),
    # the clutch reads the heating section (its friction tables): both are built per run
    ("clutch_heating.heat_capacity=30 J/K:50 J/K:3", {"clutch", "clutch_heating"}),
])
def test_only_the_elements_a_swept_key_reaches_are_built_per_run(spec, rebuilt):
    runs = SweepRuns(load_scenario(WINDOW, sweeps=[spec]))
    plans = bp.block_plans(runs, [0, 1, 2])
    sections = [section for section, _, _ in bp.element_sections(runs.scenario(0))]
    assert {sections[k] for k in plans.rebuilt} == rebuilt


@pytest.mark.parametrize("spec", ["simulation.rtol=1e-6,1e-8", "initial.motor_speed=100 rpm,200 rpm"])
def test_a_sweep_of_the_simulation_or_the_start_is_built_run_by_run(spec):
    runs = SweepRuns(load_scenario(FORCES, sweeps=[spec]))
    assert bp.block_plans(runs, [0, 1]) is None


def test_a_missed_dependency_is_caught_and_the_block_built_run_by_run(monkeypatch):
    monkeypatch.setattr(bp, "reached_sections", lambda scenario, keys: set())
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
    # tables of different lengths do not stack; the clutch reading the heating section is built with it
    (BRAKE, ["clutch.engagement_force=[[[0 s, 0 N], [0.6 s, 5 kN]], 4 kN]"], False),
    (WINDOW, ["clutch_heating.heat_capacity=30 J/K:50 J/K:3"], False),
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

"""Modelica's Rotational examples (scenarios/modelica/) against Dymola's published trajectories
(tests/data/modelica/, from modelica/MAP-LIB_ReferenceResults; its source in SOURCE.md).

Every comparison signal within 1e-3 of its range at every reference row more than 1 ms from a reference event
(a repeated time), and every switch within 1e-4 s of the reference's.  First, FirstGrounded and Backlash are
checked with their parts in tests/machine/test_springs.py; CoupledClutches here, its clutches' modes too.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers import SCENARIOS
from modelica_reference import deviations, signals
from modelica_reference import events as _events
from modelica_reference import reference as _reference

from hoistsim import load_scenario, simulate


def mode_changes(example: str, element: str) -> np.ndarray:
    """The instants the reference's mode of ``element`` changes (Modelica's mode: -1 sliding backwards, 0 stuck,
    1 forwards, 2 free)."""
    reference = _reference(example)
    return reference["time"][1:][np.diff(reference[f"{element}.mode"]) != 0.0]


# example -> the parts whose mode changes are compared with our switches (its comparison signals: the package's,
# hoistsim.references.modelica_signals)
MODED = {"Friction": ("clutch", "brake"), "OneWayClutch": (), "SimpleGearShift": ("clutch", "brake"),
         "OneWayClutchDisengaged": ()}


@pytest.mark.slow  # a program of its own to compile for each (some 6 s)
@pytest.mark.parametrize("example", sorted(MODED))
def test_an_example_against_dymolas_published_trajectories(example):
    """Every comparison signal within 1e-3 of its range (measured: within 8.3e-5), every switch of the parts
    whose modes the reference gives within 1e-4 s of its mode change, and the ledger closed."""
    run = simulate(load_scenario(SCENARIOS / "modelica" / f"{example}.yaml"))
    worst = deviations(run, example, signals(example, run))
    assert max(worst.values()) < 1e-3, worst
    for element in MODED[example]:
        changes = mode_changes(example, element)
        ours = run.events["time"][run.events["element"] == element]
        assert len(ours) == len(changes), (element, ours, changes)
        np.testing.assert_allclose(ours, changes, rtol=0, atol=1e-4, err_msg=element)
    assert run.summary["energy_relative_residual"] < 1e-9


@pytest.mark.slow  # three clutches: a program of its own to compile (~10 s)
def test_coupled_clutches_against_dymolas_published_trajectories():
    """MSL 4.0's CoupledClutches (sin2's phase pi/2): J1's angle and speed and each clutch's phi_rel, w_rel (the
    second shaft's less the first's) within 1.2e-5 of their ranges; each clutch's mode changes (Modelica's
    mode: -1 sliding backwards, 0 stuck, 1 forwards, 2 free) at hoistsim's switches, within 4e-6 s."""
    run = simulate(load_scenario(SCENARIOS / "modelica" / "CoupledClutches.yaml"))
    reference = _reference("CoupledClutches")
    times = reference["time"]
    events = _events(times)
    far = np.min(np.abs(times[:, None] - events[None, :]), axis=1) > 1e-3
    for signal, series in signals("CoupledClutches", run).items():
        worst = np.max(np.abs(np.interp(times, run.time, series) - reference[signal])[far]) / np.ptp(reference[signal])
        assert worst < 1e-3, (signal, worst)
    for k in (1, 2, 3):
        mode = reference[f"clutch{k}.mode"]
        changes = times[1:][np.diff(mode) != 0.0]
        ours_k = run.events["time"][run.events["element"] == f"clutch{k}"]
        assert len(ours_k) == len(changes), (k, ours_k, changes)
        np.testing.assert_allclose(ours_k, changes, rtol=0, atol=1e-4, err_msg=f"clutch{k}")
    assert run.summary["energy_relative_residual"] < 1e-9


@pytest.mark.parametrize("path", sorted((SCENARIOS / "modelica").glob("*.yaml")), ids=lambda p: p.stem)
def test_every_shaft_of_an_example_writes_its_angle_and_speed(path):
    """Modelica's phi and w of every inertia are series here: <shaft>_angle and <shaft>_speed for every shaft."""
    from hoistsim.machine.assemble import build_plan

    scenario = load_scenario(path)
    columns = build_plan(scenario, summary_only=True)[0].layout.columns()
    for shaft in scenario.drivetrain.shafts:
        assert f"{shaft}_angle" in columns and f"{shaft}_speed" in columns, (path.stem, shaft)


@pytest.mark.slow  # five examples' programs to compile (some 40 s)
@pytest.mark.parametrize("example, key, value", [
    ("SimpleGearShift", "drivetrain.planetaries.idealPlanetary.teeth", [40, 80]),
    ("SimpleGearShift", "drivetrain.torques.1.quadratic.nominal_torque", "-30 N*m"),
    ("EddyCurrentBrake", "drivetrain.eddy_current_brakes.eddyCurrentTorque.nominal_torque", "80 N*m"),
    ("EddyCurrentBrake", "drivetrain.heat_capacitors.heatCapacitor.heat_capacity", "2 J/K"),
    ("ElasticBearing", "drivetrain.gears.idealGear.ratio", 4),
    ("LossyGearDemo3", "drivetrain.gears.gear.loss_table", [["0 rad/s", 0.3, 0.2, "0.5 N*m", "2 N*m"]]),
    ("RollingWheel", "drivetrain.load.drag.force", "12 N"),
    ("Friction", "drivetrain.springs.spring.stiffness", "200 N*m/rad"),
])
def test_a_new_value_of_a_new_key_compiles_nothing(example, key, value):
    """A planetary set's teeth, a quadratic torque's, an eddy-current brake's and a heat capacitor's numbers, a
    housed stage's ratio, a loss table's values, a drag's force, a spring's stiffness: traced numbers, the
    example's program serving the new value (one more run, no new trace)."""
    from hoistsim.machine.core import loop

    path = SCENARIOS / "modelica" / f"{example}.yaml"
    simulate(load_scenario(path))
    before = loop.trace_count
    changed = simulate(load_scenario(path, overrides={key: value}))
    assert loop.trace_count == before, key
    assert changed.summary["energy_relative_residual"] < 1e-9

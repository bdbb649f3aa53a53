"""One compiled loop per structure: new forces, loads or tolerances never recompile."""

from __future__ import annotations

import pytest
from helpers import SCENARIOS, scene

from hoistsim import simulate
from hoistsim.machine.core import loop


@pytest.mark.slow
def test_new_parameter_values_do_not_recompile():
    simulate(scene(force="3000 N", mass="500 kg", duration="1 s"))
    before = loop.trace_count
    for force, mass, rtol in [("4500 N", "300 kg", 1e-9), ("1200 N", "700 kg", 1e-7), ("9000 N", "0 kg", 1e-8)]:
        simulate(scene(force=force, mass=mass, duration="1 s", rtol=rtol))
    assert loop.trace_count == before


@pytest.mark.slow
def test_force_table_values_do_not_recompile():
    simulate(scene(force=[["0 s", "0 N"], ["0.2 s", "4000 N"]], duration="1 s"))
    before = loop.trace_count
    simulate(scene(force=[["0.1 s", "0 N"], ["0.5 s", "7000 N"]], mass="250 kg", duration="1 s"))
    assert loop.trace_count == before


@pytest.mark.slow
def test_a_new_switch_budget_compiles_nothing_and_still_bounds_the_run():
    """simulation.max_switches is a traced bound (the passes a run may take are worked out in the loop, the event
    log's rows do not depend on it): 2, 200 and 5000 share one program and give the same run, and a budget below
    the switches the scene makes (the clutch engages, then locks) still stops it as chattering."""
    from hoistsim.running.simulation import SimulationError
    from hoistsim.scenario.loading import load_scenario

    engaging = SCENARIOS / "engage_at_speed_with_brake.yaml"
    base = simulate(load_scenario(engaging))
    before = loop.trace_count
    for budget in (2, 5000):
        again = simulate(load_scenario(engaging, overrides=[f"simulation.max_switches={budget}"]))
        assert again.summary == base.summary
    with pytest.raises(SimulationError, match="more than 1 mode switches"):
        simulate(load_scenario(engaging, overrides=["simulation.max_switches=1"]))
    assert loop.trace_count == before

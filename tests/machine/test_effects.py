"""Elements assemble only their own parts: a scene without `brake:` contains nothing of it."""

from __future__ import annotations

import jax
import numpy as np
import pytest
from helpers import scene, reduced

from hoistsim import simulate
from hoistsim.machine.assemble import build_plan, log_rows, step_room
from hoistsim.machine.core import loop
from hoistsim.machine.elements import HoldingBrake, elements_for


def _jaxpr_size(s) -> int:
    plan, _ = build_plan(s)
    run = loop.compiled_run(s.simulation.solver, log_rows(plan), step_room(plan))
    return len(str(jax.make_jaxpr(run)(plan)).splitlines())


@pytest.mark.slow
def test_scene_without_brake_has_no_brake_anywhere():
    bare = scene(force=[["0 s", "0 N"], ["0.3 s", "0 N"], ["0.3 s", "5000 N"]])
    assert not any(isinstance(e, HoldingBrake) for e in elements_for(bare))
    plan, _ = build_plan(bare)
    # no traced input of the brake ...
    assert "brake" not in plan.layout.sections
    assert not any("brake" in name for name in plan.layout.state_names)
    # ... no output column ...
    run = simulate(bare)
    assert not any(name.startswith("brake") for name in run.series)
    assert "brake_release" not in run.events["kind"]
    # ... and no term in the compiled program: the same scene with a brake compiles to more
    braked = scene(force=[["0 s", "0 N"], ["0.3 s", "0 N"], ["0.3 s", "5000 N"]], brake="0.5 s")
    assert _jaxpr_size(bare) < _jaxpr_size(braked)


@pytest.mark.slow
def test_brake_contributes_boundary_event_and_outputs():
    s = scene(force=[["0 s", "0 N"], ["0.3 s", "0 N"], ["0.3 s", "5000 N"]], brake="0.5 s")
    (brake,) = [e for e in elements_for(s) if isinstance(e, HoldingBrake)]
    assert brake.release_time == 0.5
    run = simulate(s)
    assert list(run.events["kind"][:2]) == ["engage", "brake_release"]
    assert list(run.events["element"][:2]) == ["clutch", "brake"]
    assert run.units["brake_torque"] == "N*m"
    held = run.time < 0.5
    # while held the drum does not move and the brake carries what the clutch does not
    assert np.all(run["drum_speed"][held] == 0.0)
    assert np.all(run["brake_engaged"][held] == 1) and np.all(run["brake_engaged"][~held] == 0)
    d = reduced(run)
    expected = (d.load_torque - run["clutch_torque"][held]) * d.ratio
    np.testing.assert_allclose(run["brake_torque"][held], expected, rtol=1e-12)
    assert np.all(run["brake_torque"][~held] == 0.0)


@pytest.mark.slow
def test_brake_released_at_start_is_an_event_at_zero():
    run = simulate(scene(force="5000 N", brake="0 s"))
    assert run.events["kind"][0] == "brake_release" and run.events["time"][0] == 0.0
    assert run["drum_speed"][1] > 0.0

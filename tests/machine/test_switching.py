"""Many lock/unlock cycles follow the exact solution; a switch storm is reported, not looped."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import scene

from hoistsim import SimulationError, exact_from_scenario, simulate


def oscillating_force(period=0.1, high=9000.0, low=300.0, cycles=12):
    table = []
    for k in range(cycles):
        t = k * period
        table += [[f"{t} s", f"{high} N"], [f"{t + period / 2} s", f"{low} N"]]
    return table


@pytest.mark.slow
def test_force_oscillating_across_the_threshold_matches_exact():
    s = scene(force=oscillating_force(), mass="300 kg", duration="1.2 s")
    run, exact = simulate(s), exact_from_scenario(s)
    kinds = list(run.events["kind"])
    assert kinds == [e.kind for e in exact.events]
    assert kinds.count("unlock") >= 5 and kinds.count("lock") >= 5
    np.testing.assert_allclose(run.events["time"], [e.time for e in exact.events], atol=1e-8, rtol=0)
    assert run.energy_balance["relative_residual"] < 1e-8


@pytest.mark.slow
def test_switch_cap_reports_chattering():
    s = scene(force=oscillating_force(), mass="300 kg", duration="1.2 s", max_switches=4)
    with pytest.raises(SimulationError, match="chatters: more than 4 mode switches"):
        simulate(s)

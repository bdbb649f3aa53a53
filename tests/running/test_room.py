"""A run that takes more steps than its room keeps is run again with room for them all; the next run of the
same structure starts with that room, instead of overflowing again and being run twice every time."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hoistsim import simulate
from hoistsim.running import simulation
from hoistsim.scenario.loading import load_scenario

# A block dragged by a clutch to the ground and pulled through a spring: it sticks and slips again and again,
# some 2 900 steps for 2 001 rows (room for 2 048 at first).
STICK_SLIP = Path(__file__).resolve().parents[1] / "data" / "stick_slip_chain.yaml"


def test_a_run_that_outgrew_its_room_starts_the_next_time_with_room_for_its_steps(monkeypatch):
    scenario = load_scenario(STICK_SLIP)
    monkeypatch.setattr(simulation, "_ROOM_NEEDED", {})
    called = []
    executable = simulation._jax.executable

    def counted(program, *args, name, **options):
        called.append(name)
        return executable(program, *args, name=name, **options)

    monkeypatch.setattr(simulation._jax, "executable", counted)
    first = simulate(scenario)
    assert len(called) == 2 and called[0] != called[1]  # the first room overflowed: run again with more
    second = simulate(scenario)
    assert called[2:] == called[1:2]  # once, with the room the first run needed
    assert first.stats["steps"] == second.stats["steps"]
    for name, values in first.series.items():
        np.testing.assert_array_equal(values, second.series[name])

"""One compiled loop per structure: new forces, loads or tolerances never recompile."""

from __future__ import annotations

import pytest
from helpers import scene

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

"""Comparing two results files dataset by dataset: the same numbers, bit for bit (a resumed or clustered
sweep against the one-process, uninterrupted one)."""

from __future__ import annotations

import h5py
import numpy as np
from conftest import SCENARIOS

from hoistsim import load_scenario

SWEEP_FILE = SCENARIOS / "force_sweep_engage_at_speed.yaml"
CLOCKS = {"solver_wall_time"}  # the only numbers that differ between two runs of the same sweep


def short_sweep(count: int):
    """The engagement-force sweep, 0.4 s runs, ``count`` forces from 3 to 12 kN."""
    return load_scenario(SWEEP_FILE, overrides=["simulation.duration=0.4 s"],
                         sweeps=[f"clutch.engagement_force=3 kN:12 kN:{count}"])


def datasets(path) -> dict:
    """Every dataset of a results file but the clocks and the scenario text (which names the command)."""
    out = {}
    with h5py.File(path, "r") as f:
        def visit(name, item):
            if isinstance(item, h5py.Dataset) and name.rsplit("/", 1)[-1] not in CLOCKS and name != "scenario":
                out[name] = item.asstr()[()] if item.dtype.kind == "O" else item[()]
        f.visititems(visit)
    return out


def same(a: dict, b: dict) -> None:
    assert sorted(a) == sorted(b)
    for name in a:
        if a[name].dtype.kind == "f":
            np.testing.assert_array_equal(a[name], b[name], err_msg=name)  # NaN where NaN, bits elsewhere
        else:
            assert (a[name] == b[name]).all(), name

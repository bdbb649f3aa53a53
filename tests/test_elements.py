"""New elements against independent answers, and the core's promises about elements.

Each element is checked against something that does not use it: a flywheel
against the same inertia given to the shaft directly, a rim against its
formula, a torque-speed table against the linear motor it lies on, a motor
that is off against the closed form of two inertias meeting through a
slipping clutch.
"""

from __future__ import annotations

import copy
import math
import re
from pathlib import Path

import numpy as np
import pytest
from scenes import EXERCISE6

from hoistsim import scenario_from_dict, simulate
from hoistsim.assemble import build_plan, check_couplings
from hoistsim.core.element import AbstractCoupling
from hoistsim.core.layout import Layout
from hoistsim.elements import REGISTRY, elements_for
from hoistsim.errors import ScenarioError

TIGHT = {"rtol": 1e-10, "atol": 1e-12}
# A start that slips, locks, and lifts: every mode of the clutch and a moving drum.
RAMP = [["0 s", "0 N"], ["0.2 s", "0 N"], ["0.6 s", "6000 N"]]


def _scene(**sections):
    data = copy.deepcopy(EXERCISE6)
    data["clutch"]["engagement_force"] = RAMP
    data["simulation"].update(duration="1.5 s", **TIGHT)
    for key, value in sections.items():
        if value is None:
            data.pop(key, None)
        elif isinstance(value, dict) and isinstance(data.get(key), dict):
            data[key].update(value)
            data[key] = {k: v for k, v in data[key].items() if v is not None}
        else:
            data[key] = value
    return scenario_from_dict(data)


def _speeds(run):
    return run["motor_speed"], run["drum_speed"]


class _SecondBrake(AbstractCoupling):
    """A brake on the pinion shaft: with a brake on the drum, the same motion held twice."""

    section = "pinion_brake"
    can_slip = False

    def joins(self):
        return ("pinion", None)

    def capacity(self, x):
        return math.inf

    def sliding_torque(self, x):
        return 0.0


def test_couplings_holding_the_same_motion_twice_are_refused():
    s = _scene(brake={"release_time": "0.5 s"})
    elements = elements_for(s) + (_SecondBrake(),)
    with pytest.raises(ScenarioError, match="pinion_brake: would hold a motion that clutch, brake already holds"):
        check_couplings(Layout(elements))
    check_couplings(Layout(elements_for(s)))  # the clutch and one brake are independent


def test_the_core_names_no_part_of_the_machine():
    core = Path(__file__).resolve().parents[1] / "hoistsim" / "core"
    for path in core.glob("*.py"):
        text = path.read_text(encoding="utf-8")
        found = re.findall(r"\b(clutch|brake|load|motor|drum|pinion|gear)\w*", text, flags=re.IGNORECASE)
        assert not found, f"{path.name} names {sorted(set(found))}"


def test_every_element_is_one_file_named_after_it():
    folder = Path(__file__).resolve().parents[1] / "hoistsim" / "elements"
    classes = [c for entry in REGISTRY.values() for c in (entry.values() if isinstance(entry, dict) else [entry])]
    for cls in classes:
        module = cls.__module__.rsplit(".", 1)[-1]
        assert (folder / f"{module}.py").exists()
        assert sum(1 for c in classes if c.__module__ == cls.__module__) == 1, module

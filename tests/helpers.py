"""What the tests share, in one place: where things are, the exercise-6 scenes and scenario texts they start
from, the settings of the property searches, and two results files compared bit for bit.

Every test imports it the same way from whichever folder of tests/ it is in (conftest.py puts this folder on
the path): ``from helpers import SCENARIOS, scene``.
"""

from __future__ import annotations

import copy
import os
import re
from pathlib import Path

import h5py
import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from hoistsim import load_scenario, scenario_from_dict

# ------------------------------------------------------------------------------------------- where things are
TESTS = Path(__file__).resolve().parent  # hard/ (the hard cases' scenes) and data/ (outside references) too
ROOT = TESTS.parent
SCENARIOS = ROOT / "scenarios"
EXERCISE6_FILE = SCENARIOS / "exercise6_direct_start.yaml"



def docs_checker():
    """docs/check_readme.py, the pages' commands' reader and runner, as a module (loaded once a process)."""
    import importlib.util
    import sys

    if "check_readme" not in sys.modules:
        spec = importlib.util.spec_from_file_location("check_readme", ROOT / "docs" / "check_readme.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # its dataclasses look their module up there
        spec.loader.exec_module(module)
    return sys.modules["check_readme"]


# ------------------------------------------------------------------------------------ exercise 6 as a text
SHIPPED = EXERCISE6_FILE.read_text(encoding="utf-8")  # as a user has it


def core(text: str) -> str:
    """A scenario text without its optional sections (they may come and go in the shipped files)."""
    kept, skipping = [], False
    for line in text.splitlines(keepends=True):
        top = re.match(r"([A-Za-z_]\w*)[ \t]*:", line)
        if top:
            skipping = top.group(1) in ("initial", "brake", "bearings", "sweep")
        if not skipping:
            kept.append(line)
    return "".join(kept)


BASE = core(SHIPPED)  # what the tests of bad input edit
SHORT = SHIPPED.replace("  duration: 3 s\n", "  duration: 0.4 s\n", 1)  # a run in a blink: watch, the pool
TIGHT = ["simulation.rtol=1e-10", "simulation.atol=1e-12"]  # --set: the tolerances of a check against a reference


def line_of(text: str, fragment: str) -> int:
    """The line (from 1) of a text on which ``fragment`` first stands."""
    return text[: text.index(fragment)].count("\n") + 1


def with_force(text: str, newtons: int) -> str:
    """A scenario text with its clutch's engagement force set to ``newtons``."""
    lines = [f"  engagement_force: {newtons} N" if line.strip().startswith("engagement_force:") else line
             for line in text.splitlines()]
    return "\n".join(lines) + "\n"


# ------------------------------------------------------------------------------- exercise 6 as a scene
EXERCISE6 = {
    "name": "test-scene",
    "motor": {"stall_torque": "500 N*m", "no_load_speed": "300 rpm", "inertia": "0.9 kg*m^2"},
    "clutch": {
        "inner_radius": "20 cm", "outer_radius": "24 cm", "half_angle": "25 deg",
        "static_friction": 0.3, "kinetic_friction": 0.1, "engagement_force": "3201 N",
    },
    "gears": {"pinion_teeth": 17, "wheel_teeth": 90, "module": "4 mm", "pressure_angle": "20 deg"},
    "drum": {"diameter": "40 cm", "inertia": "40 kg*m^2"},
    "load": {"mass": "500 kg"},
    "simulation": {"duration": "2 s", "output_interval": "5 ms", "rtol": 1e-10, "atol": 1e-12},
}


def scene(force="3201 N", mass="500 kg", motor_speed=None, brake=None, duration="2 s", name="test-scene",
          **simulation):
    """A validated scenario; ``force`` is anything the engagement_force key accepts."""
    data = copy.deepcopy(EXERCISE6)
    data["name"] = name
    data["clutch"]["engagement_force"] = force
    data["load"]["mass"] = mass
    data["simulation"]["duration"] = duration
    data["simulation"].update(simulation)
    if motor_speed is not None:
        data["initial"] = {"motor_speed": motor_speed}
    if brake is not None:
        data["brake"] = {"release_time": brake}
    return scenario_from_dict(data, name=name)


# -------------------------------------------------------------------------------- a drawn drivetrain
def drawn(name: str, duration="1 s", interval="1 ms", rtol=1e-11, atol=1e-13, **parts):
    """A drawn drivetrain of ``parts`` (the keys of ``drivetrain:``) at tight tolerances, for checks of its
    parts against closed forms and independent integrations."""
    return scenario_from_dict({"name": name, "drivetrain": parts, "simulation": {
        "duration": duration, "output_interval": interval, "rtol": rtol, "atol": atol}}, name=name)


# -------------------------------------------------------------------------------- a bad scenario refused
def part_keys_set(kind: str, name: str, keys: dict):
    """A change for :func:`refused_in_one_line`: drivetrain.<kind>.<name>'s ``keys`` set (None: removed)."""
    def change(data):
        part = data["drivetrain"][kind][name]
        for key, value in keys.items():
            part.pop(key) if value is None else part.update({key: value})
    return change


def refused_in_one_line(path, change, key: str, says: str, tmp_path) -> None:
    """The scenario file ``path`` with ``change(data)`` made to its plain data is refused naming ``key`` (its
    message saying ``says``): by the loader, and by ``hoistsim run`` in one line, exit 2, nothing written."""
    import pytest
    from click.testing import CliRunner
    from ruamel.yaml import YAML

    from hoistsim.cli import main
    from hoistsim.errors import ScenarioError

    data = YAML(typ="safe").load(Path(path).read_text(encoding="utf-8"))
    change(data)
    bad, out = tmp_path / "bad.yaml", tmp_path / "out.h5"
    with bad.open("w", encoding="utf-8") as f:
        YAML().dump(data, f)
    with pytest.raises(ScenarioError) as raised:
        load_scenario(bad)
    assert raised.value.key == key and says in str(raised.value), str(raised.value)
    result = CliRunner().invoke(main, ["run", str(bad), "-o", str(out)])
    assert result.exit_code == 2 and len(result.output.strip().splitlines()) == 1 and key in result.output
    assert not out.exists()


# ----------------------------------------------------------------------------------- property searches
def property_settings(examples: int, **more) -> settings:
    """``examples`` random scenes a property in CI; HOISTSIM_PROPERTY_EXAMPLES=400 for a deeper search by hand.
    With ``derandomize=True``, the same scenes every run of the same code (see _draws_from_the_strategies_alone)."""
    if more.get("derandomize"):
        _draws_from_the_strategies_alone()
    return settings(max_examples=int(os.environ.get("HOISTSIM_PROPERTY_EXAMPLES", str(examples))), deadline=None,
                    suppress_health_check=[HealthCheck.too_slow], **more)


engagement_forces = st.one_of(  # a constant, or a ramp from nothing to a force that is then held
    st.floats(200.0, 15000.0).map(lambda f: f"{f} N"),
    st.tuples(st.floats(0.02, 0.8), st.floats(500.0, 15000.0)).map(
        lambda r: [["0 s", "0 N"], [f"{r[0]} s", f"{r[1]} N"]]),
)

# -------------------------------------------------------------------- two results files, bit for bit
# (a resumed or clustered sweep against the one-process, uninterrupted one)
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


def reduced(run):
    """The two-shaft reduced model of a run's scenario (:mod:`hoistsim.references.model`): the oracles' numbers."""
    from hoistsim.references.model import Machine

    return Machine.from_scenario(run.scenario).reduced()


def _draws_from_the_strategies_alone():
    """Hypothesis also draws numbers it finds in the modules a process has imported (each module's literal
    constants), and which test modules a worker has imported depends on the files it ran before: the same
    derandomized search drew other chains from one run of the suite to the next, on the same code.  With that
    pool empty, its draws are the strategies' and the seed's alone.  The pool is private to Hypothesis: where
    it is gone, nothing is changed."""
    from hypothesis.internal.conjecture import providers

    if callable(getattr(providers, "_get_local_constants", None)) and hasattr(providers, "CONSTANTS_CACHE"):
        nothing = providers.Constants()
        providers._get_local_constants = lambda: nothing
        providers.CONSTANTS_CACHE.cache.clear()  # the pools drawn from so far

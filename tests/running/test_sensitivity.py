"""Derivatives through every switch, against the closed form's own derivatives and against finite differences."""

from __future__ import annotations

import math

import pytest
from helpers import EXERCISE6_FILE, SCENARIOS

from hoistsim import exact_from_scenario, load_scenario
from hoistsim.errors import ScenarioError
from hoistsim.running.sensitivity import sensitivity

ENGAGE = SCENARIOS / "engage_at_speed_with_brake.yaml"
TIGHT = ["simulation.rtol=1e-11", "simulation.atol=1e-13"]
SI = {"clutch.engagement_force": "N", "clutch.kinetic_friction": "", "load.mass": "kg", "motor.inertia": "kg*m^2",
      "motor.rotor_mass": "kg", "motor.radius_of_gyration": "m"}


def _setting(path, key, x) -> str:
    """``--set`` text giving ``key`` the number ``x`` (SI); engage-at-speed's force table scaled to a peak of x."""
    if key == "clutch.engagement_force" and path == ENGAGE:
        return f"{key}=[[0 s, 0 N], [0.5 s, 0 N], [0.6 s, {x!r} N]]"
    return f"{key}={x!r} {SI[key]}".rstrip()


def _exact(path, overrides, key=None, x=None):
    """The closed form's lock-up time and clutch heat, with ``key`` set to ``x`` (SI)."""
    extra = [_setting(path, key, x)] if key else []
    solution = exact_from_scenario(load_scenario(path, overrides=overrides + extra))
    locks = [e.time for e in solution.events if e.kind == "lock"]
    return {"lockup_time": locks[0] if locks else math.nan, "slip_energy": solution.final["clutch_energy"]}


def _exact_derivative(path, overrides, key, x, name):
    """The closed form's derivative: central differences at h and h/2, extrapolated (error ~h^4)."""
    def central(h):
        return (_exact(path, overrides, key, x + h)[name] - _exact(path, overrides, key, x - h)[name]) / (2 * h)

    h = 1e-3 * abs(x)
    return (4 * central(h / 2) - central(h)) / 3


CASES = [
    # the motor started with the drum held, the clutch ramped on, the brake released: one lock
    # (the force a table: the derivative with respect to its peak, the table scaled with it)
    (ENGAGE, [], ["lockup_time", "slip_energy"],
     ["clutch.engagement_force", "clutch.kinetic_friction", "load.mass", "motor.inertia"]),
    # exercise 6 started direct-on-line below the force that carries the stall torque: it slips throughout
    (EXERCISE6_FILE, ["clutch.engagement_force=2000 N"], ["slip_energy"],
     # the rotor's inertia from its mass and radius of gyration: the second enters squared
     ["clutch.engagement_force", "clutch.kinetic_friction", "load.mass", "motor.rotor_mass",
      "motor.radius_of_gyration"]),
]


@pytest.mark.parametrize("path, overrides, names, keys", CASES, ids=["engage at speed", "direct start"])
def test_the_derivatives_are_the_closed_forms(path, overrides, names, keys):
    result = sensitivity(load_scenario(path, overrides=overrides + TIGHT), keys, of=names)
    for name in names:
        for key in keys:
            expected = _exact_derivative(path, overrides, key, result.keys[key], name)
            assert result.derivatives[name][key] == pytest.approx(expected, rel=1e-6), (name, key)


def test_a_lock_moves_with_the_friction_as_finite_differences_of_the_run_say():
    """The lock-up time against central differences of hoistsim's own runs (the
    difference converging on the derivative as the step shrinks)."""
    from hoistsim import simulate

    s = load_scenario(ENGAGE, overrides=TIGHT)
    result = sensitivity(s, ["clutch.kinetic_friction"], of=["lockup_time"])
    x = result.keys["clutch.kinetic_friction"]
    errors = []
    for h in (1e-3, 1e-4, 1e-5):
        ends = [simulate(load_scenario(ENGAGE, overrides=TIGHT + [f"clutch.kinetic_friction={x + d!r}"])).values
                for d in (h, -h)]
        errors.append(abs((ends[0]["lockup_time"] - ends[1]["lockup_time"]) / (2 * h)
                          - result.derivatives["lockup_time"]["clutch.kinetic_friction"]))
    assert errors[1] < errors[0] / 50 and errors[2] < errors[1] / 50  # as h squared
    assert errors[2] < 1e-6 * abs(result.derivatives["lockup_time"]["clutch.kinetic_friction"])


def test_a_summary_that_does_not_exist_has_no_derivative():
    s = load_scenario(EXERCISE6_FILE, overrides=["clutch.engagement_force=2000 N"])
    result = sensitivity(s, ["load.mass"], of=["lockup_time", "slip_energy"])
    assert math.isnan(result.values["lockup_time"]) and math.isnan(result.derivatives["lockup_time"]["load.mass"])
    assert math.isfinite(result.derivatives["slip_energy"]["load.mass"])


@pytest.mark.parametrize("keys, of, message", [
    (["clutch.nonsense"], None, "clutch.nonsense"),
    (["brake.release_time", "load.gravity"], None, "load.gravity"),
    (["gears.pinion_teeth"], None, "is a count (17)"),
    (["clutch"], None, "is a section"),
    (["name"], None, "not a number"),
    (["load.mass"], ["load_lifted"], "yes/no"),
    (["load.mass"], ["no_such_summary"], "no summary"),
])
def test_a_key_or_summary_that_has_no_derivative_is_refused(keys, of, message):
    with pytest.raises(ScenarioError) as caught:
        sensitivity(load_scenario(ENGAGE), keys, of=of)
    assert message in str(caught.value)


def test_the_command_prints_the_derivatives_and_their_elasticities():
    """`hoistsim sensitivity`: the table names each key and summary with the derivative's units, and --json gives
    the same numbers as the Python call (the scene and keys of the closed-form test: its compiled program)."""
    import json

    from click.testing import CliRunner

    from hoistsim.cli import main
    from hoistsim.results.report import fmt

    keys = ["clutch.kinetic_friction", "load.mass", "motor.inertia"]
    args = ["sensitivity", str(ENGAGE), "--wrt", ",".join(keys), "--of", "lockup_time,slip_energy",
            *(option for pair in TIGHT for option in ("--set", pair))]
    shown = CliRunner(env={"COLUMNS": "80"}).invoke(main, args)
    assert shown.exit_code == 0, shown.output
    assert max(len(line) for line in shown.stdout.splitlines()) <= 80, shown.stdout  # the notes wrapped too
    assert "d/d load.mass" in shown.stdout and "s/kg" in shown.stdout and "J/(kg*m^2)" in shown.stdout
    assert "elasticity" in shown.stdout and "clutch.kinetic_friction = 0.1" in shown.stdout
    printed = json.loads(CliRunner().invoke(main, [*args, "--json"]).stdout)
    result = sensitivity(load_scenario(ENGAGE, overrides=TIGHT), keys, of=["lockup_time", "slip_energy"])
    # {summary: {"value": v, "unit": u, key: {derivative, elasticity, unit}}}
    assert set(printed) == {"lockup_time", "slip_energy"}
    for name, unit in (("lockup_time", " s"), ("slip_energy", " J")):  # the value the table prints, its unit
        assert printed[name]["value"] == result.values[name] and printed[name]["unit"] == unit.strip()
        assert f"{fmt(result.values[name], 6)}{unit}" in shown.stdout
    for name in ("lockup_time", "slip_energy"):
        for key in keys:
            entry = printed[name][key]
            assert entry["derivative"] == result.derivatives[name][key]
            assert entry["elasticity"] == pytest.approx(result.elasticity(name, key), rel=1e-15)
    assert printed["lockup_time"]["load.mass"]["unit"] == "s/kg"


def test_a_bad_key_ends_the_command_at_one_line():
    from click.testing import CliRunner

    from hoistsim.cli import main

    done = CliRunner().invoke(main, ["sensitivity", str(ENGAGE), "--wrt", "load.mass,name"])
    assert done.exit_code == 2
    assert done.stderr.strip().splitlines() == [
        "hoistsim: error: --wrt name: holds 'engage-at-speed-with-brake', not a number: a derivative is taken "
        "with respect to a number"]


@pytest.mark.slow
def test_the_series_derivatives_are_written_and_meet_finite_differences(tmp_path):
    """`--series -o OUT.h5`: each series' derivative on the run's rows, as a variable of the results file with
    units, against central differences of the runs on the grid's rows (away from the lock's instant, where
    the series has a corner and a difference across it means nothing)."""
    import numpy as np
    from click.testing import CliRunner

    from hoistsim import open_results, simulate
    from hoistsim.cli import main

    out = tmp_path / "sensitivity.h5"
    done = CliRunner().invoke(main, ["sensitivity", str(ENGAGE), "--wrt", "load.mass,clutch.kinetic_friction",
                                     "--of", "lockup_time", "--series", "-o", str(out)])
    assert done.exit_code == 0, done.output
    data = open_results(out)
    assert data["d_motor_speed_d_load.mass"].attrs["units"] == "rad/s/kg"
    assert "d_clutch_locked_d_load.mass" not in data  # a flag has no derivative
    base = simulate(load_scenario(ENGAGE))
    h = 0.05  # kg
    up, down = (simulate(load_scenario(ENGAGE, overrides=[f"load.mass={500 + d!r}"])) for d in (h, -h))
    lock = base.values["lockup_time"]
    rows = base.grid_rows()
    away = np.abs(base.time[rows] - lock) > 0.002
    derivative = data["d_motor_speed_d_load.mass"].values.ravel()[:rows.size]
    difference = (up["motor_speed"][up.grid_rows()] - down["motor_speed"][down.grid_rows()]) / (2 * h)
    scale = np.max(np.abs(derivative))
    assert scale > 0 and np.max(np.abs(difference - derivative)[away]) < 1e-5 * scale

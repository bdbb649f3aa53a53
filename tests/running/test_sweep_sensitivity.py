"""Sensitivities on every run of a sweep: each run's as one run's own, the derivatives as summary columns."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SCENARIOS

from hoistsim import load_scenario
from hoistsim.cli import main
from hoistsim.errors import ScenarioError
from hoistsim.running.sensitivity import sensitivity
from hoistsim.scenario.sweep_runs import SweepRuns

ENGAGE = SCENARIOS / "engage_at_speed_with_brake.yaml"
TIGHT = ["simulation.rtol=1e-11", "simulation.atol=1e-13"]
# the keys of test_sensitivity's command test: the single run's compiled program is the same
KEYS = ["clutch.kinetic_friction", "load.mass", "motor.inertia"]
OF = ["lockup_time", "slip_energy"]
# at 1 500 kg the kinetic clutch passes less torque than the load needs: it runs back, no lock-up
SWEEP = "\nsweep:\n  load.mass: [300 kg, 500 kg, 1500 kg]\n"


@pytest.fixture(scope="module")
def swept(tmp_path_factory):
    path = tmp_path_factory.mktemp("swept") / "engage_swept.yaml"
    path.write_text(ENGAGE.read_text(encoding="utf-8") + SWEEP, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def result(swept):
    return sensitivity(load_scenario(swept, overrides=TIGHT), KEYS, of=OF)


def _as_single_runs(result, runs, setting):
    """Every run's values and derivatives against the single run's at that run's values (``setting(i)``: its
    --set), to round-off (the vectorised program sums in another order)."""
    for i in range(len(runs)):
        one = sensitivity(load_scenario(ENGAGE, overrides=TIGHT + [setting(i)]), KEYS, of=OF)
        run = result[i]
        assert run.keys == one.keys
        for name in OF:
            assert run.values[name] == pytest.approx(one.values[name], rel=1e-12, nan_ok=True)
            for key in KEYS:
                scale = np.nanmax(np.abs(result.derivatives[name][key]))
                if math.isnan(one.derivatives[name][key]):
                    assert math.isnan(run.derivatives[name][key]), (i, name, key)
                else:
                    assert abs(run.derivatives[name][key] - one.derivatives[name][key]) < 1e-9 * scale, (i, name, key)


def test_each_run_is_differentiated_as_one_run_is(swept, result):
    """A swept key among the keys: each run's directions from its own plans (the swept key's at each run's own
    value), the keys that reach no swept element the first run's."""
    runs = SweepRuns(load_scenario(swept, overrides=TIGHT))
    assert list(result.wrt["load.mass"]) == [300.0, 500.0, 1500.0]
    _as_single_runs(result, runs, lambda i: f"load.mass={float(result.wrt['load.mass'][i])!r} kg")


def test_a_sweep_of_another_key_builds_its_plans_from_the_first_runs(tmp_path):
    """No key swept: the plans either side of the swept clutch's kinetic friction built for every run at once
    from the first run's (as a summary-only sweep builds its plans), the load's and motor's directions the
    first run's; each run as one run."""
    from hoistsim.running import sweep_sensitivity

    path = tmp_path / "static_swept.yaml"
    path.write_text(ENGAGE.read_text(encoding="utf-8") + "\nsweep:\n  clutch.static_friction: [0.25, 0.3, 0.35]\n",
                    encoding="utf-8")
    scenario = load_scenario(path, overrides=TIGHT)
    runs = SweepRuns(scenario)
    first = runs.scenario(0)
    assert sweep_sensitivity._unreached_keys(runs, first, KEYS) == {"load.mass", "motor.inertia"}
    assert sweep_sensitivity._from_template(runs, first, None, [], {}, set()) is not None  # the template applies
    result = sensitivity(scenario, KEYS, of=OF)
    _as_single_runs(result, runs, lambda i: f"clutch.static_friction={(0.25, 0.3, 0.35)[i]!r}")


def test_a_run_without_the_summary_has_no_derivative_and_the_others_do(result):
    assert math.isnan(result.values["lockup_time"][2])  # the 1500 kg load runs back
    assert all(math.isnan(result.derivatives["lockup_time"][key][2]) for key in KEYS)
    assert all(math.isfinite(result.derivatives["lockup_time"][key][k]) for key in KEYS for k in (0, 1))
    assert all(math.isfinite(result.derivatives["slip_energy"][key][2]) for key in KEYS)  # it slips throughout
    elasticity = result.elasticity("lockup_time", "load.mass")
    assert elasticity[1] == pytest.approx(500.0 / result.values["lockup_time"][1]
                                          * result.derivatives["lockup_time"]["load.mass"][1], rel=1e-15)


def test_the_command_prints_a_table_a_summary_and_writes_the_derivatives_as_summary_columns(swept, result, tmp_path):
    """`hoistsim sensitivity SWEEP.yaml -o OUT.h5`: the summary-only file of the sweep, its summaries as a sweep
    writes them and each derivative a column with units; --json: a run's entry as one run's --json."""
    import xarray as xr

    out = tmp_path / "derivatives.h5"
    args = ["sensitivity", str(swept), "--wrt", ",".join(KEYS), "--of", ",".join(OF),
            *(option for pair in TIGHT for option in ("--set", pair))]
    shown = CliRunner().invoke(main, [*args, "-o", str(out)])
    assert shown.exit_code == 0, shown.output
    assert ", 3 runs: how each summary moves" in shown.stdout and "load.mass=1500 kg" in shown.stdout
    assert "d/d" in shown.stdout and "[s/kg]" in shown.stdout and "elasticity" in shown.stdout
    data = xr.open_dataset(out, group="runs", engine="h5netcdf")
    assert data["d_lockup_time_d_load.mass"].attrs["units"] == "s/kg"
    assert data["d_slip_energy_d_motor.inertia"].attrs["units"] == "J/(kg*m^2)"
    assert data["d_lockup_time_d_load.mass"].attrs["long_name"] == ("derivative of the time the clutch first locks "
                                                                    "with respect to load.mass")
    assert "NaN: never locked" in data["lockup_time"].attrs["comment"]  # the summaries in words, as a run's file
    np.testing.assert_array_equal(data["d_slip_energy_d_clutch.kinetic_friction"].values,
                                  result.derivatives["slip_energy"]["clutch.kinetic_friction"])
    np.testing.assert_array_equal(data["load.mass"].values, [300.0, 500.0, 1500.0])
    assert {"lock_events", "energy_relative_residual", "final_load_position"} <= set(data.data_vars)
    # the same sweep given on the command line
    args = [*args[:1], str(ENGAGE), *args[2:], "--sweep", "load.mass=300 kg,500 kg,1500 kg"]
    printed = json.loads(CliRunner().invoke(main, [*args, "--json"]).stdout)
    assert [run["label"] for run in printed["runs"]] == result.labels
    assert printed["runs"][1]["summary"] == result[1].to_dict()
    assert printed["runs"][2]["summary"]["lockup_time"]["load.mass"]["derivative"] is None


@pytest.mark.parametrize("extra, message", [
    (["--series", "-o", "x.h5"], "--series: the series' derivatives are of one run"),
    (["-o", "x.csv"], "x.csv: the results file must be named .h5"),
    (["--of", "load_lifted"], "yes/no"),
])
def test_what_a_sweep_cannot_give_ends_at_one_line(swept, extra, message, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    done = CliRunner().invoke(main, ["sensitivity", str(swept), "--wrt", "load.mass", *extra])
    assert done.exit_code == 2 and message in done.stderr
    assert len(done.stderr.strip().splitlines()) == 1 and not list(tmp_path.iterdir())


def test_an_empty_key_list_is_refused_for_a_sweep(swept):
    with pytest.raises(ScenarioError, match="--wrt"):
        sensitivity(load_scenario(swept), [], of=OF)


@pytest.mark.slow
def test_runs_of_different_structures_are_differentiated_apart(tmp_path):
    """A sweep of force tables of different lengths: each length its own compiled program, every run's
    derivative as its single run's."""
    path = tmp_path / "tables.yaml"
    path.write_text(ENGAGE.read_text(encoding="utf-8") + (
        "\nsweep:\n  clutch.engagement_force:\n"
        "    - [[0 s, 0 N], [0.5 s, 0 N], [0.6 s, 5000 N]]\n"
        "    - [[0 s, 0 N], [0.5 s, 0 N], [0.55 s, 3000 N], [0.6 s, 6000 N]]\n"
        "    - [[0 s, 0 N], [0.5 s, 0 N], [0.6 s, 7000 N]]\n"), encoding="utf-8")
    keys = ["clutch.kinetic_friction", "clutch.engagement_force"]
    swept = sensitivity(load_scenario(path), keys, of=["lockup_time"])
    assert swept.tables == ("clutch.engagement_force",)
    assert list(swept.wrt["clutch.engagement_force"]) == [5000.0, 6000.0, 7000.0]  # each table's largest force
    for i, run in enumerate(SweepRuns(load_scenario(path)).scenario(i) for i in range(3)):
        one = sensitivity(run, keys, of=["lockup_time"])
        for key in keys:
            assert swept.derivatives["lockup_time"][key][i] == pytest.approx(one.derivatives["lockup_time"][key],
                                                                             rel=1e-9)

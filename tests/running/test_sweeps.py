"""Vectorised sweeps: same answers as single runs, no recompilation, exact summaries, files and tables."""

from __future__ import annotations

import csv
import io
import math

import h5py
import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SCENARIOS, SWEEP_FILE, scene

from hoistsim import exact_from_scenario, load_scenario, simulate, sweep
from hoistsim.cli import main
from hoistsim.machine.core import loop
from hoistsim.scenario.sweep_runs import SweepRuns, sweep_values

@pytest.fixture(scope="module")
def full():
    return sweep(load_scenario(SWEEP_FILE))


@pytest.mark.slow
def test_sweep_runs_equal_single_runs(full):
    """vmap changes nothing: each run of the sweep is the run simulated alone."""
    for (label, one), run in zip(sweep_values(full.scenario), full.runs):
        alone = simulate(one, label=label)
        assert run.label == label
        np.testing.assert_allclose(run.time, alone.time, rtol=0, atol=1e-12)
        for name in ("motor_speed", "drum_speed", "clutch_energy", "clutch_torque"):
            np.testing.assert_allclose(run[name], alone[name], rtol=1e-12, atol=1e-9, err_msg=name)
        assert list(run.events["kind"]) == list(alone.events["kind"])


@pytest.mark.slow
def test_summary_only_gives_the_same_summaries(full):
    brief = sweep(full.scenario, summary_only=True)
    assert brief.runs is None and brief.labels == full.labels
    for a, b in zip(brief.summaries, full.summaries):
        for key, value in a.items():
            if isinstance(value, float) and math.isnan(value):
                assert math.isnan(b[key]), key
            elif isinstance(value, float):
                assert value == pytest.approx(b[key], rel=1e-10, abs=1e-9), key
            else:
                assert value == b[key], key


@pytest.mark.slow
def test_summaries_match_the_exact_solution():
    s = load_scenario(SWEEP_FILE, sweeps=["clutch.engagement_force=3 kN:12 kN:40"])
    result = sweep(s, summary_only=True)
    for (_, one), summary in zip(sweep_values(s), result.summaries):
        exact = exact_from_scenario(one)
        assert summary["slip_energy"] == pytest.approx(exact.slip_energy, rel=1e-7)
        if math.isnan(exact.lockup_time):
            assert math.isnan(summary["lockup_time"])
        else:
            assert summary["lockup_time"] == pytest.approx(exact.lockup_time, abs=1e-7)
        assert summary["final_motor_speed"] == pytest.approx(exact.final["motor_speed"], abs=1e-5)
        assert summary["lock_events"] == sum(e.kind == "lock" for e in exact.events)
    assert any(math.isnan(r["lockup_time"]) for r in result.summaries)  # the weakest runs back
    locks = [r["lockup_time"] for r in result.summaries if not math.isnan(r["lockup_time"])]
    assert locks == sorted(locks, reverse=True)  # more force, earlier lock-up


@pytest.mark.slow
def test_new_sweep_values_do_not_recompile():
    s = load_scenario(SWEEP_FILE, sweeps=["clutch.engagement_force=4 kN:8 kN:16"])
    sweep(s, summary_only=True)
    before = loop.trace_count
    for spec in ("clutch.engagement_force=5 kN:11 kN:16", "load.mass=100 kg:900 kg:16"):
        sweep(load_scenario(SWEEP_FILE, sweeps=[spec]), summary_only=True)
    assert loop.trace_count == before


@pytest.mark.slow
def test_two_keys_give_a_grid_and_tables_of_different_length_share_a_call():
    s = load_scenario(SWEEP_FILE, sweeps=["clutch.engagement_force=[5 kN, [[0 s, 0 N], [0.2 s, 8000 N]]]",
                                          "load.mass=200 kg,400 kg"], overrides={"simulation.duration": "0.5 s"})
    result = sweep(s)
    assert len(result) == 4 and result.labels[1].endswith("load.mass=400 kg")
    for (label, one), run in zip(sweep_values(s), result.runs):
        assert run.slip_energy == pytest.approx(exact_from_scenario(one).slip_energy, rel=1e-6)
    assert np.isnan(result.parameters["clutch.engagement_force"][2])  # a table has no single value


@pytest.mark.slow
def test_chunks_do_not_change_answers():
    s = load_scenario(SWEEP_FILE, sweeps=["clutch.engagement_force=3 kN:12 kN:11"])
    a = sweep(s, summary_only=True, chunk_size=4)  # 3 chunks, the last padded
    b = sweep(s, summary_only=True)
    assert [r["slip_energy"] for r in a.summaries] == [r["slip_energy"] for r in sweep(
        s, summary_only=True, chunk_size=4).summaries]  # the same chunks: the same bits
    # another width: the same to round-off (XLA may fuse multiply-adds differently at another vector width)
    np.testing.assert_allclose([r["slip_energy"] for r in a.summaries], [r["slip_energy"] for r in b.summaries],
                               rtol=1e-13)
    np.testing.assert_allclose(a.summary["lockup_time"], b.summary["lockup_time"], rtol=0, atol=1e-14)


def test_cli_sweep_summary_only_compare_and_plot(tmp_path):
    out = tmp_path / "big.h5"
    result = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(out), "--summary-only",
                                       "--sweep", "clutch.engagement_force=3 kN:12 kN:64"])
    assert result.exit_code == 0, result.output
    assert "64 runs" in result.output and "..." in result.output  # a long table is shortened
    with h5py.File(out, "r") as f:
        assert "time" not in f["runs"] and f["runs/lockup_time"].shape == (64,)  # no series, the run variables
        assert f["runs/clutch.engagement_force"][-1] == pytest.approx(12000.0)
        assert f["runs/clutch.engagement_force"].attrs["units"] == "N"
    table = CliRunner(env={"COLUMNS": "120"}).invoke(main, ["compare", str(out)])
    assert table.exit_code == 0
    lines = table.output.splitlines()
    assert max(len(line) for line in lines) <= 120  # fits a terminal
    rule = next(i for i, line in enumerate(lines) if line.startswith("---"))  # units under the names, above it
    # every run, named by its swept value (its label says no more)
    forces = [line.split()[0] for line in lines[rule + 1:-1]]
    assert len(forces) == 64 and (forces[0], forces[-1]) == ("3000", "12000")
    assert lines[rule - 1].split()[:2] == ["[N]", "[s]"] and lines[-1].startswith("(") and "--columns" in lines[-1]
    chosen = CliRunner().invoke(main, ["compare", str(out), "--columns", "label,slip_energy,lockup_time"])
    assert [line.split() for line in chosen.output.splitlines()[:3]] == [["clutch"], ["run", "heat", "lock-up"],
                                                                         ["[kJ]", "[s]"]]  # as `run` heads them
    rows = list(csv.DictReader(io.StringIO(CliRunner().invoke(main, ["compare", str(out), "--csv"]).output)))
    units, rows = rows[0], rows[1:]  # a units row under the header
    assert units["clutch.engagement_force"] == "N" and units["slip_energy"] == "J" and units["label"] == ""
    assert len(rows) == 64 and float(rows[0]["clutch.engagement_force"]) == pytest.approx(3000.0)
    figure = tmp_path / "big.png"
    plotted = CliRunner().invoke(main, ["plot", str(out), "-o", str(figure)])
    assert plotted.exit_code == 0, plotted.output
    assert figure.stat().st_size > 10_000  # a summary-only file: the summary figure alone


@pytest.mark.slow
def test_plot_of_a_sweep_writes_histories_and_summary(tmp_path):
    out = tmp_path / "sweep.h5"
    assert CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(out),
                                     "--set", "simulation.duration=0.5 s"]).exit_code == 0
    result = CliRunner().invoke(main, ["plot", str(out), "-o", str(tmp_path / "f.svg")])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "f.svg").exists() and (tmp_path / "f_summary.svg").exists()


@pytest.mark.slow
def test_progress_only_on_a_terminal(tmp_path):
    result = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(tmp_path / "x.h5"), "--summary-only"])
    assert result.exit_code == 0 and "runs (" not in result.output  # not a tty: no progress line


@pytest.mark.slow
def test_python_api_for_notebooks(tmp_path):
    result = sweep(scene(force="5000 N", motor_speed="300 rpm", duration="0.5 s"))
    assert len(result) == 1 and result.runs[0].summary["lock_events"] == 1
    result.to_hdf5(tmp_path / "one.h5")
    assert result.summary["slip_energy"].shape == (1,)


@pytest.mark.slow
def test_a_sweep_is_one_dataset_in_memory_and_in_its_file(tmp_path):
    """SweepResult.to_xarray() and hoistsim.open_results() of its file hold the same (run, time) series
    and (run) values; runs of different durations share one time axis, NaN where a run has no row."""
    import hoistsim

    base = load_scenario(SWEEP_FILE, sweeps=["simulation.duration=0.3 s,0.5 s"])
    result = sweep(base)
    result.to_hdf5(tmp_path / "two.h5")
    memory = result.to_xarray()
    with hoistsim.open_results(tmp_path / "two.h5") as ds:
        assert ds["slip_speed"].dims == ("run", "time") and ds.sizes == {"run": 2, "time": 501}
        np.testing.assert_array_equal(ds["slip_speed"].values, memory["slip_speed"].values)
        np.testing.assert_array_equal(ds["simulation.duration"].values, [0.3, 0.5])
        assert ds["simulation.duration"].attrs["units"] == "s" and ds["slip_energy"].attrs["units"] == "J"
        assert np.isnan(ds["slip_speed"].values[0, 301:]).all() and np.isfinite(ds["slip_speed"].values[1]).all()
        np.testing.assert_array_equal(ds["lockup_time"].values, memory["lockup_time"].values)
        assert list(ds["label"].values) == list(memory["label"].values)


@pytest.mark.parametrize("spec, words", [
    ("clutch.engagement_force=1 kN:9 kg:5", "cannot make a range"),
    ("clutch.engagement_force=1 kN:9 kN:x", "whole number"),
    ("clutch.engagement_force=1 kN:9 kN:0", "from 1 to 1000000"),
    ("clutch.engagement_force=[1 kN, 2 kg]", "value 2 (2 kg): expected a force"),
    ("load.mas=1 kg,2 kg", "did you mean load.mass?"),
    ("clutch.engagement_force=", "needs values"),
])
def test_bad_sweep_on_the_command_line_is_one_line_naming_sweep(tmp_path, spec, words):
    out = tmp_path / "never.h5"
    result = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(out), "--sweep", spec])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error: --sweep: ") and words in lines[0], lines
    assert not out.exists()


def test_range_in_a_file_needs_from_to_and_count(tmp_path):
    text = SWEEP_FILE.read_text().replace("{from: 3 kN, to: 12 kN, count: 10}", "{from: 3 kN, to: 12 kN}")
    path = tmp_path / "range.yaml"
    path.write_text(text)
    result = CliRunner().invoke(main, ["run", str(path), "-o", str(tmp_path / "x.h5")])
    line = next(i for i, row in enumerate(text.splitlines(), 1) if "{from: 3 kN" in row)
    assert result.exit_code == 2 and f"range.yaml:{line}: sweep.clutch.engagement_force:" in result.output


@pytest.mark.slow
def test_an_observation_never_fires_again_at_its_own_restart():
    """The slip of this start settles towards a steady value, its rate passing through zero at 0.29 s.

    Vectorised, round-off once left the slip-valley guard slightly positive at
    the restart on its own root, so it fired again at once, 200 times without
    progress, until the observation budget ran out (and the whole chunk waited).
    A guard that ended a pass now starts the next at or below zero.
    """
    import jax

    from hoistsim.machine.assemble import build_plan
    from hoistsim.machine.core.readout import PASSES
    from hoistsim.running.blocks import compiled_batch

    s = load_scenario(SWEEP_FILE, sweeps=["clutch.engagement_force=3510.2639296187685 N"])
    ((_, one),) = sweep_values(s)
    plan, _ = build_plan(one, summary_only=True)
    batch = jax.tree.map(lambda leaf: np.stack([leaf]), plan)
    raw = jax.device_get(compiled_batch(s.simulation.solver, 1, 1, False)(batch))
    assert int(raw.counters[0, PASSES]) <= 4
    assert sweep(s, summary_only=True).summaries[0]["slip_duration"] == pytest.approx(2.0)


def test_a_chunk_split_over_devices_gives_each_run_its_answer(monkeypatch):
    """Each CPU device runs its share of a chunk through its own loop: the runs' answers are those of the
    chunk on one device (to round-off: XLA compiles the split program on its own), in sweep order."""
    import jax

    from hoistsim.running import blocks

    assert jax.device_count() == 2  # conftest asks for two
    assert [blocks.devices_for(chunk) for chunk in (1, 2, 8)] == [1, 2, 2]
    s = load_scenario(SWEEP_FILE, overrides=["simulation.duration=0.4 s"],
                      sweeps=["clutch.engagement_force=3 kN:12 kN:12"])
    split = sweep(s, summary_only=True, chunk_size=16).summary
    monkeypatch.setattr(blocks, "devices_for", lambda chunk: 1)
    alone = sweep(s, summary_only=True, chunk_size=16).summary
    assert np.count_nonzero(~np.isnan(alone["lockup_time"])) >= 6  # most runs lock, some slip to the end
    np.testing.assert_allclose(split["lockup_time"], alone["lockup_time"], rtol=0, atol=1e-12)
    for name in ("slip_energy", "final_motor_speed", "final_drum_speed", "peak_clutch_torque"):
        np.testing.assert_allclose(split[name], alone[name], rtol=1e-12, err_msg=name)
    assert list(split["label"]) == list(alone["label"])


def test_loading_a_sweep_costs_in_proportion_to_its_values(monkeypatch):
    """Each swept value is validated alone, once, on the validated base: the scenario's plain data is not
    copied per value (it was, with the whole sweep in it: 1 000 force tables took 18 s to load)."""
    from hoistsim.scenario import loading as scenario_module
    from hoistsim.scenario import sweep_spec, yamlsource

    calls = {"copies": 0, "values": 0}
    original_copy, original_value = yamlsource.copy_plain, sweep_spec.with_swept_value

    def counting_copy(data):
        calls["copies"] += 1
        return original_copy(data)

    def counting_value(*args, **kwargs):
        calls["values"] += 1
        return original_value(*args, **kwargs)

    monkeypatch.setattr(yamlsource, "copy_plain", counting_copy)
    monkeypatch.setattr(sweep_spec, "_copy_plain", counting_copy)
    monkeypatch.setattr(sweep_spec, "with_swept_value", counting_value)
    text = SWEEP_FILE.read_text().split("\nsweep:")[0]

    def load(count):
        calls.update(copies=0, values=0)
        tables = "".join(f"\n    - [[0 s, 0 N], [0.05 s, {3000 + 10 * i} N]]" for i in range(count))
        scenario_module.scenario_from_text(text + "\nsweep:\n  clutch.engagement_force:" + tables + "\n")
        return dict(calls)

    small, large = load(40), load(160)
    assert (small["values"], large["values"]) == (40, 160)  # each value validated once
    assert large["copies"] == small["copies"]  # the plain data is copied as often whatever the sweep's size


def test_a_range_of_temperatures_is_spaced_in_kelvin_not_scaled_from_zero():
    # degC has an offset: the values between the ends are 313.15 K, not 40 * 274.15 K
    s = load_scenario(SCENARIOS / "clutch_force_window.yaml",
                      sweeps=["clutch_heating.initial_temperature=20 degC:60 degC:3"])
    np.testing.assert_allclose(SweepRuns(s).parameters["clutch_heating.initial_temperature"],
                               [293.15, 313.15, 333.15], rtol=1e-12)

"""The HDF5 file matches the contract, opens in xarray, and is written atomically."""

from __future__ import annotations

import json
import os
import signal
import stat
import subprocess
import sys
import textwrap

import h5py
import numpy as np
import pytest
from helpers import SCENARIOS, scene

from hoistsim import load_scenario, simulate
from hoistsim.results.output import write_runs

CONTRACT_SERIES = ["motor_speed", "drum_speed", "slip_speed", "clutch_torque", "clutch_locked",
                   "engagement_force", "load_position", "load_velocity", "clutch_energy"]
CONTRACT_RUN_VARIABLES = ["label", "lockup_time", "slip_energy"]
EVENT_COLUMNS = ["run", "time", "kind", "element", "torque_margin", "mode_after"]


@pytest.fixture(scope="module")
def braked_run():
    return simulate(load_scenario(SCENARIOS / "engage_at_speed_with_brake.yaml"))


@pytest.fixture(scope="module")
def written(braked_run, tmp_path_factory):
    path = tmp_path_factory.mktemp("out") / "run.h5"
    braked_run.to_hdf5(path)
    return path


def test_file_has_contract_names_and_units(written, braked_run):
    """Format 2: the series on (run, time), the run's numbers on (run), the instants in /runs/events."""
    with h5py.File(written, "r") as f:
        assert f.attrs["format_version"] == 2
        group = f["runs"]
        grid = group["time"][()]
        assert np.all(np.diff(grid) > 0) and grid[-1] == 3.0 and grid.size == 3001  # the output grid only
        for name in CONTRACT_SERIES:
            assert group[name].shape == (1, grid.size), name
        for name in CONTRACT_RUN_VARIABLES:
            assert group[name].shape == (1,), name
        for name, data in group.items():
            if isinstance(data, h5py.Dataset):
                assert "units" in data.attrs, name
        assert group["clutch_torque"].attrs["units"] == "N*m" and group["lockup_time"].attrs["units"] == "s"
        assert group["lockup_time"][0] == pytest.approx(braked_run.lockup_time)
        assert json.loads(group.attrs["parameters"])["brake"]["release_time"] == 0.6
        for attr in ("name", "solver", "rtol", "atol"):
            assert attr in group.attrs, attr
        events = group["events"]
        for name in EVENT_COLUMNS:
            assert name in events, name
        switches = events["category"].asstr()[()] != "observation"
        assert list(events["kind"].asstr()[()][switches]) == ["engage", "brake_release", "lock"]
        assert events["time"][()][switches][1] == 0.6
        observations = set(events["kind"].asstr()[()][~switches])
        assert observations == {"slip_peak"}  # the slip's peak as the clutch closes, an exact instant
        scenario = f["scenario"]
        text = scenario[()].decode() if isinstance(scenario[()], bytes) else scenario[()]
        assert "release_time: 0.6 s" in text
        for attr in ("hoistsim_version", "jax_version", "diffrax_version", "created", "solver", "rtol", "atol"):
            assert attr in scenario.attrs, attr


def test_each_instant_carries_the_state_just_after_it(written, braked_run):
    """The lock's row in the events table holds the speeds just after the lock: equal, no slip."""
    with h5py.File(written, "r") as f:
        events = f["runs/events"]
        kinds = list(events["kind"].asstr()[()])
        lock = kinds.index("lock")
        assert events["time"][lock] == pytest.approx(braked_run.lockup_time, abs=0)
        assert events["slip_speed"][lock] == pytest.approx(0.0, abs=1e-9)
        assert events["clutch_locked"][lock] == 1 and events["mode_after"].asstr()[lock] == "locked"
        row = int(np.searchsorted(braked_run.time, events["time"][lock]))
        assert events["motor_speed"][lock] == braked_run["motor_speed"][row]


def test_opens_in_xarray_as_one_dataset(written):
    import xarray as xr

    import hoistsim

    with hoistsim.open_results(written) as ds:
        assert ds["motor_speed"].dims == ("run", "time") and ds["lockup_time"].dims == ("run",)
        assert ds["clutch_torque"].attrs["units"] == "N*m"
        assert float(ds["time"][-1]) == 3.0
        assert ds["clutch_locked"].dtype == np.int8  # a flag stays a flag
        one = ds.sel(run=0)
        assert float(one["lockup_time"]) > 1.0
    with xr.open_dataset(written, group="runs/events", engine="h5netcdf") as events:
        assert "lock" in list(events["kind"].values)


def _summary_names(group) -> list[str]:
    """The summary variables of a file's /runs: its summary columns less the label and the swept keys."""
    swept = json.loads(group.attrs["swept_keys"])
    return [name for name in json.loads(group.attrs["summary_columns"]) if name != "label" and name not in swept]


def test_every_summary_says_what_it_is_and_what_its_0_and_nan_mean(written, braked_run, tmp_path):
    """Each summary variable (and every other) carries a long_name beside its units, in h5py and in xarray; a
    lock-up time says that 0 is a clutch locked from the start and NaN one that never locked.  A summary-only
    file's too."""
    import types

    import hoistsim
    from hoistsim.results.output import write_sweep
    from hoistsim.results.summaries import Summaries

    only = tmp_path / "summaries.h5"
    write_sweep(only, types.SimpleNamespace(scenario=braked_run.scenario, labels=["a"], parameters={}, runs=None,
                                            summaries=Summaries.from_rows([braked_run.summary]),
                                            summary_units=braked_run.summary_units))
    for path in (written, only):
        with h5py.File(path, "r") as f:
            names = _summary_names(f["runs"])
            assert len(names) >= 10 and "lockup_time" in names and "energy_relative_residual" in names
            for name, data in f["runs"].items():  # the summary, and every other variable too
                if isinstance(data, h5py.Dataset):
                    assert str(data.attrs.get("long_name", "")).strip(), name
            comment = f["runs/lockup_time"].attrs["comment"]
            assert "0: locked from the start" in comment and "NaN: never locked" in comment
            assert "comment" not in f["runs/peak_clutch_torque"].attrs  # a plain number: nothing to say
        with hoistsim.open_results(path) as ds:
            assert all(ds[name].attrs["long_name"] for name in names)
            assert ds["lockup_time"].attrs["long_name"] == "time the clutch first locks"
            assert "NaN: never locked" in ds["lockup_time"].attrs["comment"]


def test_every_summary_of_every_shipped_scenario_has_a_meaning():
    """The words come from the summaries' name patterns: a part's new summary without them fails here."""
    from hoistsim.results.summary_meanings import summary_meaning
    from hoistsim.running.simulation import scene_summary_units

    for path in sorted(SCENARIOS.glob("*.yaml")):
        for name in scene_summary_units(load_scenario(path)):
            assert summary_meaning(name)[0], (path.name, name)
    assert summary_meaning("clutch2_lockup_time") == ("time clutch2 first locks", summary_meaning("lockup_time")[1])
    assert summary_meaning("d_lockup_time_d_load.mass")[0] == ("derivative of the time the clutch first locks with "
                                                               "respect to load.mass")


def test_reading_back_gives_the_run_as_simulated(written, braked_run):
    """The grid rows and the instants merge back into the run's own rows, value for value."""
    from hoistsim.results.reading import read_runs

    (back,) = read_runs(written)
    np.testing.assert_array_equal(back["time"], braked_run.time)
    for name in ("motor_speed", "slip_speed", "clutch_torque", "brake_torque", "clutch_mode"):
        np.testing.assert_array_equal(back[name], braked_run[name])


def test_runs_in_memory_read_as_their_file_does(braked_run, tmp_path):
    """What `watch` draws from while the file is written: the rows, the instants and the summary, value for
    value and type for type, as reading the file back gives them."""
    from hoistsim.results.reading import read_runs
    from hoistsim.results.run_dicts import run_dicts

    path = tmp_path / "two.h5"
    write_runs(path, [braked_run, braked_run])
    for columns in (None, {"motor_speed", "clutch_mode", "brake_torque"}):
        from_file, in_memory = read_runs(path, columns=columns), run_dicts([braked_run, braked_run], columns=columns)
        assert len(from_file) == len(in_memory) == 2
        for back, made in zip(from_file, in_memory):
            assert set(back) == set(made)
            for name in set(back) - {"events", "attrs"}:
                assert back[name].dtype == made[name].dtype, name
                np.testing.assert_array_equal(back[name], made[name], err_msg=name)
            assert back["events"].dtype == made["events"].dtype and len(back["events"]) >= 3
            for field in back["events"].dtype.names:
                if back["events"].dtype[field].kind == "f":
                    np.testing.assert_array_equal(back["events"][field], made["events"][field], err_msg=field)
                else:
                    assert list(back["events"][field]) == list(made["events"][field]), field
            assert set(back["attrs"]) == set(made["attrs"])
            for key, value in back["attrs"].items():
                assert type(made["attrs"][key]) is type(value), key
                assert made["attrs"][key] == value or (value != value and made["attrs"][key] != made["attrs"][key]), key


@pytest.mark.slow
def test_sweep_of_runs_and_summary(tmp_path):
    runs = [simulate(scene(force=f"{f} N", duration="0.5 s"), label=f"clutch.engagement_force={f} N")
            for f in (2500, 4000)]
    path = tmp_path / "sweep.h5"
    write_runs(path, runs)
    with h5py.File(path, "r") as f:
        assert f["runs/motor_speed"].shape == (2, 101)  # 0.5 s on a 5 ms grid
        labels = list(f["runs/label"].asstr()[()])
        assert labels == ["clutch.engagement_force=2500 N", "clutch.engagement_force=4000 N"]


def test_failed_write_leaves_existing_file_and_no_debris(tmp_path, braked_run, monkeypatch):
    path = tmp_path / "keep.h5"
    path.write_bytes(b"precious results")
    from hoistsim.results import output

    def broken(*args, **kwargs):
        raise RuntimeError("disk fell off")

    monkeypatch.setattr(output.Assembly, "_instants", broken)
    with pytest.raises(RuntimeError):
        write_runs(path, [braked_run])
    assert path.read_bytes() == b"precious results"
    assert os.listdir(tmp_path) == ["keep.h5"]


@pytest.mark.slow
def test_killed_writer_leaves_existing_file_intact(tmp_path):
    """A process killed (SIGKILL) in the middle of writing leaves the old file as it was."""
    path = tmp_path / "results.h5"
    path.write_bytes(b"the previous results")
    script = textwrap.dedent(f"""
        import os, signal
        from hoistsim import load_scenario, simulate
        from hoistsim.results import output
        run = simulate(load_scenario({str(SCENARIOS / 'runback_slipping_clutch.yaml')!r}))
        def die(*args, **kwargs):
            os.kill(os.getpid(), signal.SIGKILL)   # half-way through the file
        output.Assembly._instants = die
        output.write_runs({str(path)!r}, [run])
    """)
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True)
    assert proc.returncode == -signal.SIGKILL
    assert path.read_bytes() == b"the previous results"


def test_run_to_xarray_has_time_coordinate_and_units(braked_run):
    pytest.importorskip("xarray")
    ds = braked_run.to_xarray()
    assert ds["slip_speed"].dims == ("time",) and ds["time"].attrs["units"] == "s"
    assert ds["brake_torque"].attrs["units"] == "N*m"
    np.testing.assert_array_equal(ds["motor_speed"].values, braked_run["motor_speed"])


@pytest.mark.parametrize("umask", [0o022, 0o077, 0o002])
def test_a_written_file_has_the_mode_the_umask_allows(tmp_path, umask):
    """Results are written to a temporary file and renamed: the rename must not keep mkstemp's 0600."""
    from hoistsim.results.output import atomic_path

    old = os.umask(umask)
    try:
        with atomic_path(tmp_path / "out.h5") as path:
            path.write_bytes(b"results")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "out.h5").stat().st_mode) == 0o666 & ~umask

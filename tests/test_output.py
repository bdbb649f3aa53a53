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
from conftest import SCENARIOS
from scenes import scene

from hoistsim import load_scenario, simulate
from hoistsim.output import write_runs

CONTRACT_SERIES = ["time", "motor_speed", "drum_speed", "slip_speed", "clutch_torque", "clutch_locked",
                   "engagement_force", "load_position", "load_velocity", "clutch_energy"]
CONTRACT_ATTRS = ["name", "label", "parameters", "lockup_time", "slip_energy", "solver", "rtol", "atol"]


@pytest.fixture(scope="module")
def braked_run():
    return simulate(load_scenario(SCENARIOS / "engage_at_speed_with_brake.yaml"))


@pytest.fixture(scope="module")
def written(braked_run, tmp_path_factory):
    path = tmp_path_factory.mktemp("out") / "run.h5"
    braked_run.to_hdf5(path)
    return path


def test_file_has_contract_names_and_units(written, braked_run):
    with h5py.File(written, "r") as f:
        group = f["runs/0"]
        for name in CONTRACT_SERIES:
            assert name in group, name
            assert group[name].shape == group["time"].shape
        for name, data in group.items():
            assert "units" in data.attrs, name
        for attr in CONTRACT_ATTRS:
            assert attr in group.attrs, attr
        assert np.all(np.diff(group["time"][()]) > 0)
        assert json.loads(group.attrs["parameters"])["brake"]["release_time"] == 0.6
        assert group.attrs["lockup_time"] == pytest.approx(braked_run.lockup_time)
        events = group["events"][()]
        kinds = [k.decode() if isinstance(k, bytes) else k for k in events["kind"]]
        assert kinds == ["engage", "brake_release", "lock"]
        assert events["time"][1] == 0.6
        assert "units" in f["summary"].attrs and f["summary"].shape == (1,)
        scenario = f["scenario"]
        text = scenario[()].decode() if isinstance(scenario[()], bytes) else scenario[()]
        assert "release_time: 0.6 s" in text
        for attr in ("hoistsim_version", "jax_version", "diffrax_version", "created", "solver", "rtol", "atol"):
            assert attr in scenario.attrs, attr


def test_event_times_are_rows_of_the_series(written):
    with h5py.File(written, "r") as f:
        time = f["runs/0/time"][()]
        for t in f["runs/0/events"]["time"]:
            assert t in time


def test_opens_in_xarray_with_time_coordinate(written):
    xr = pytest.importorskip("xarray")
    with xr.open_dataset(written, group="runs/0", engine="h5netcdf") as ds:
        assert "time" in ds.coords
        assert ds["motor_speed"].dims == ("time",)
        assert ds["clutch_torque"].attrs["units"] == "N*m"
        assert float(ds["time"][-1]) == 3.0


@pytest.mark.slow
def test_sweep_of_runs_and_summary(tmp_path):
    runs = [simulate(scene(force=f"{f} N", duration="0.5 s"), label=f"clutch.engagement_force={f} N")
            for f in (2500, 4000)]
    path = tmp_path / "sweep.h5"
    write_runs(path, runs)
    with h5py.File(path, "r") as f:
        assert sorted(f["runs"]) == ["0", "1"]
        labels = [x.decode() if isinstance(x, bytes) else x for x in f["summary"]["label"]]
        assert labels == ["clutch.engagement_force=2500 N", "clutch.engagement_force=4000 N"]


def test_failed_write_leaves_existing_file_and_no_debris(tmp_path, braked_run, monkeypatch):
    path = tmp_path / "keep.h5"
    path.write_bytes(b"precious results")
    from hoistsim import output

    def broken(*args, **kwargs):
        raise RuntimeError("disk fell off")

    monkeypatch.setattr(output, "_write_summary", broken)
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
        from hoistsim import load_scenario, simulate, output
        run = simulate(load_scenario({str(SCENARIOS / 'runback_slipping_clutch.yaml')!r}))
        def die(*args, **kwargs):
            os.kill(os.getpid(), signal.SIGKILL)   # half-way through the file
        output._write_summary = die
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
    from hoistsim.output import atomic_path

    old = os.umask(umask)
    try:
        with atomic_path(tmp_path / "out.h5") as path:
            path.write_bytes(b"results")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "out.h5").stat().st_mode) == 0o666 & ~umask

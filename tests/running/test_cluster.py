"""A sweep on a Dask cluster: a real scheduler and two workers on 127.0.0.1, the same bits as one process."""

from __future__ import annotations

import os
import signal
import time

import h5py
import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SHORT, SWEEP_FILE, datasets, same, short_sweep, with_force

from hoistsim import sweep
from hoistsim.cli import main

distributed = pytest.importorskip("distributed")


@pytest.fixture(scope="module")
def cluster():
    """A scheduler and two worker processes, one thread each, on 127.0.0.1."""
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                  dashboard_address=":0") as running:
        yield running


@pytest.fixture
def small_blocks(monkeypatch):
    """Blocks of one chunk: a short sweep makes several, spread over both workers."""
    from hoistsim.running import sweeps

    monkeypatch.setattr(sweeps, "BLOCK_CHUNKS", 1)


@pytest.mark.slow
@pytest.mark.parametrize("summary_only", [True, False])
def test_a_sweep_on_two_workers_is_the_sweep_on_one_process(tmp_path, cluster, small_blocks, summary_only):
    scenario = short_sweep(40)
    here = sweep(scenario, summary_only=summary_only, chunk_size=4, output=tmp_path / "here.h5")
    there = sweep(scenario, summary_only=summary_only, chunk_size=4, output=tmp_path / "there.h5",
                  scheduler=cluster.scheduler_address)
    same(datasets(tmp_path / "here.h5"), datasets(tmp_path / "there.h5"))
    np.testing.assert_array_equal(here.summary["lockup_time"], there.summary["lockup_time"])
    assert list(there.summary["label"]) == list(here.summary["label"])
    with h5py.File(tmp_path / "there.h5") as f:
        assert f["runs/run"].shape == (40,)


@pytest.mark.slow
def test_a_worker_lost_mid_sweep_loses_and_duplicates_nothing(tmp_path, cluster, small_blocks):
    """One worker's process is killed (SIGKILL) after the first block comes back: Dask runs its blocks
    elsewhere (the nanny starts a new worker), and the file is the one-process file."""
    scenario = short_sweep(40)
    sweep(scenario, summary_only=True, chunk_size=4, output=tmp_path / "here.h5")
    client = distributed.Client(cluster.scheduler_address, set_as_default=False)
    killed = []

    def progress(done, total):
        if not killed:
            victim = sorted(client.scheduler_info()["workers"])[0]
            pid = client.run(os.getpid, workers=[victim])[victim]
            os.kill(pid, signal.SIGKILL)
            killed.append(victim)

    there = sweep(scenario, summary_only=True, chunk_size=4, output=tmp_path / "there.h5",
                  scheduler=cluster.scheduler_address, progress=progress)
    client.close()
    assert killed
    same(datasets(tmp_path / "here.h5"), datasets(tmp_path / "there.h5"))
    assert len(there.summaries) == 40


def test_an_unreachable_scheduler_is_one_line_and_exit_2_within_seconds(tmp_path):
    started = time.perf_counter()
    result = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(tmp_path / "out.h5"), "--summary-only",
                                       "--scheduler", "tcp://127.0.0.1:9"])
    assert time.perf_counter() - started < 15
    assert result.exit_code == 2, result.output
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error: --scheduler tcp://127.0.0.1:9: "), lines
    assert not (tmp_path / "out.h5").exists() and not list(tmp_path.iterdir())


@pytest.mark.slow
def test_the_command_line_runs_a_sweep_on_local_workers(tmp_path):
    target = tmp_path / "two.h5"
    result = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(target), "--summary-only",
                                       "--set", "simulation.duration=0.4 s", "--workers", "2",
                                       "--sweep", "clutch.engagement_force=3 kN:12 kN:12"])
    assert result.exit_code == 0, result.output
    alone = tmp_path / "one.h5"
    CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(alone), "--summary-only",
                              "--set", "simulation.duration=0.4 s",
                              "--sweep", "clutch.engagement_force=3 kN:12 kN:12"])
    same(datasets(alone), datasets(target))


def test_workers_and_scheduler_together_are_refused(tmp_path):
    result = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(tmp_path / "out.h5"), "--workers", "2",
                                       "--scheduler", "tcp://127.0.0.1:9"])
    assert result.exit_code == 2 and "give either --workers" in result.output


class _Cancelling:
    """A client whose first submission of one block is cancelled (a scheduler connection that dropped)."""

    def __init__(self, cancel_start: int):
        self.cancel_start, self.submitted = cancel_start, []

    def scatter(self, data, broadcast=False):
        return data

    def scheduler_info(self):
        return {"workers": {"a": {}, "b": {}}}

    def wait_for_workers(self, n, timeout=None):
        pass

    def submit(self, func, *args, key, pure):
        self.submitted.append(key)
        cancel = args[1] == self.cancel_start and self.submitted.count(key) == 1 and key.endswith("-1")

        class Future:
            def result(self):
                if cancel:
                    from concurrent.futures import CancelledError

                    raise CancelledError(key)
                return func(*args)

        return Future()


def test_a_block_the_cluster_cancels_is_submitted_again_and_taken_once(monkeypatch):
    from hoistsim.running import cluster

    monkeypatch.setattr(cluster, "_remote_block", lambda runs, start, stop, *how: (start, stop))
    client = _Cancelling(cancel_start=4)
    blocks = [(0, 4), (4, 8), (8, 10)]
    taken = list(cluster.cluster_blocks(client, object(), blocks, summary_only=True, chunk=4))
    assert taken == blocks  # in order, each once
    assert sum(key.split("-")[-2] == "4" for key in client.submitted) == 2  # the cancelled block again


def test_a_block_cancelled_again_and_again_stops_the_sweep_in_one_line(monkeypatch):
    from hoistsim.running import cluster

    class Always(_Cancelling):
        def submit(self, func, *args, key, pure):
            from concurrent.futures import CancelledError

            class Future:
                def result(self):
                    raise CancelledError(key)

            return Future()

    with pytest.raises(cluster.ClusterLost, match="cancelled runs 0-3 3 times"):
        list(cluster.cluster_blocks(Always(0), object(), [(0, 4)], summary_only=True, chunk=4))


def test_a_worker_with_fewer_devices_than_the_split_says_so_in_one_line():
    """A worker keeps the client's split of a chunk over devices (another split: other bits); one that lacks
    the devices stops the sweep, saying how to start it."""
    from hoistsim.running import cluster

    with pytest.raises(cluster.ClusterError, match="start the workers with HOISTSIM_CPU_DEVICES=3$"):
        cluster._remote_block(short_sweep(4), 0, 4, True, 3, 3)


def _structures_in_one_worker(scenario_text: str) -> tuple[int, int, list[float]]:
    """In a worker process: three runs, each of another structure (solver), with room for one program."""
    import os

    os.environ["HOISTSIM_MAX_PROGRAMS"] = "1"
    from hoistsim import _jax, scenario_from_text, simulate

    heats = []
    for solver in ("tsit5", "dopri5", "tsit5"):
        run = simulate(scenario_from_text(scenario_text.replace("solver: tsit5", f"solver: {solver}")))
        heats.append(run.summary["slip_energy"])
    os.environ.pop("HOISTSIM_MAX_PROGRAMS")
    return len(_jax.programs), _jax.programs.let_go, heats


@pytest.mark.slow
def test_a_worker_that_meets_more_structures_than_it_may_hold_lets_the_oldest_go(cluster):
    with distributed.Client(cluster.scheduler_address) as client:
        held, let_go, heats = client.submit(_structures_in_one_worker, with_force(SHORT, 2600), pure=False).result()
    assert held == 1 and let_go >= 2
    assert heats[0] == heats[2] and abs(heats[1] - heats[0]) < 1e-6 * heats[0]

"""A sweep's blocks on a Dask cluster: a local one (``--workers N``) or a running one (``--scheduler ADDRESS``).

Each worker is sent the sweep's description once (its base scenario and swept
values, :class:`hoistsim.scenario.sweep_runs.SweepRuns`), takes blocks of runs, builds
their scenarios and plans itself, runs them through the vectorised loop it
compiled (or loaded from the persistent cache) once, and sends back arrays:
the block's summaries, or its runs' time series (for a file, the block's
record read straight from its chunks' arrays: no run's objects made or
sent).  The client writes: blocks are taken back in sweep order, so the
file is the one a single process writes, bit for bit.  A worker lost
mid-sweep has its blocks run again elsewhere by Dask; a block the cluster
cancels (the client's connection to the scheduler dropped) is submitted
again; a block is only ever taken back once.  Dask is an optional
dependency (``pip install -e ".[cluster]"``).
"""

from __future__ import annotations

import collections
import contextlib
import uuid
from concurrent.futures import CancelledError

CONNECT_SECONDS = 5  # an address with no scheduler behind it fails this fast
RETRIES = 3  # submissions of a block the cluster cancels before the sweep gives up
WORKERS_SECONDS = 60  # a running cluster must have a worker by then


class ClusterError(Exception):
    """No cluster to run on: Dask not installed, a scheduler that does not answer, no workers."""


class ClusterLost(ClusterError):
    """The cluster went away during the sweep (its finished blocks are kept for --resume)."""


def cluster_blocks(client, runs, blocks, *, summary_only: bool, chunk: int, records: bool = False):
    """The blocks ``(start, stop)`` of ``runs`` computed on the cluster, yielded in order as they finish
    (``records``: full output as a results file's records, where the blocks' runs allow)."""
    sweep_id = uuid.uuid4().hex[:12]  # a running cluster may serve other sweeps: keys of our own
    shared = [client.scatter(runs, broadcast=True)]  # sent once to each worker, not with every block
    from .blocks import devices_for  # here: the command line names this module's errors before any sweep

    devices = devices_for(chunk)  # the client's split, kept by every worker: the same bits as one process
    window = 2 * max(1, len(client.scheduler_info()["workers"])) + 2
    tries = collections.Counter()

    def submit(start: int, stop: int):
        tries[start] += 1
        key = f"hoistsim-block-{sweep_id}-{start}-{tries[start]}"
        return (start, stop), client.submit(_remote_block, shared[0], start, stop, summary_only, chunk, devices,
                                            records, pure=False, key=key)

    def taken(block, future):
        # A block is taken back once.  Dask reruns a lost worker's tasks itself; a future it cancels
        # (the client's connection to the scheduler dropped and came back) is submitted again.
        while True:
            try:
                return future.result()
            except CancelledError:
                if tries[block[0]] >= RETRIES:
                    raise ClusterLost(f"the cluster cancelled runs {block[0]}-{block[1] - 1} "
                                       f"{RETRIES} times; the chunks written so far are kept (--resume)") from None
                client.wait_for_workers(1, timeout=WORKERS_SECONDS)
                shared[0] = client.scatter(runs, broadcast=True)  # the scattered sweep may have gone too
                block, future = submit(*block)

    pending: collections.deque = collections.deque()
    for start, stop in blocks:
        pending.append(submit(start, stop))
        if len(pending) >= window:  # bounded: at most a window of finished blocks waits for the writer
            yield taken(*pending.popleft())
    while pending:
        yield taken(*pending.popleft())


@contextlib.contextmanager
def connect(workers: int | None = None, scheduler: str | None = None):
    """A Dask client: of a local cluster of ``workers`` processes, started here, or of the running
    ``scheduler``.  Connecting comes before anything is written: a cluster that is not there is a
    one-line :class:`ClusterError`."""
    try:
        from distributed import Client, LocalCluster
    except ImportError:
        raise ClusterError("--workers and --scheduler need Dask: pip install -e \".[cluster]\"") from None
    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=f"{CONNECT_SECONDS}s", set_as_default=False)
        except (OSError, TimeoutError) as exc:
            raise ClusterError(f"--scheduler {scheduler}: no Dask scheduler answers there "
                               f"({type(exc).__name__} after {CONNECT_SECONDS} s)") from None
        with client:
            try:
                client.wait_for_workers(1, timeout=WORKERS_SECONDS)
            except TimeoutError:
                raise ClusterError(f"--scheduler {scheduler}: the cluster has no worker "
                                   f"(none joined in {WORKERS_SECONDS} s)") from None
            yield client
        return
    if workers < 1:
        raise ClusterError(f"--workers: needs at least 1, got {workers}")
    # processes with one thread each: a worker splits its chunks over a CPU device per core, as one process
    # does (hoistsim._jax), so that the numbers are the same bits; the cluster spreads blocks, not cores
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True, dashboard_address=":0",
                      host="127.0.0.1") as cluster, Client(cluster, set_as_default=False) as client:
        yield client


def _remote_block(runs, start: int, stop: int, summary_only: bool, chunk: int, devices: int, records: bool = False):
    """On a worker: one block, its chunks split over the client's ``devices`` (the programs compiled once
    per worker process, kept in the persistent cache)."""
    from .. import _jax
    from .blocks import run_block

    _jax.enable_compilation_cache()
    import jax

    if len(jax.devices()) < devices:  # another split would give other bits (to round-off)
        raise ClusterError(f"a worker has {len(jax.devices())} CPU device(s), the sweep splits its chunks over "
                           f"{devices}: start the workers with HOISTSIM_CPU_DEVICES={devices}")
    return run_block(runs, start, stop, summary_only=summary_only, chunk=chunk, devices=devices, records=records)

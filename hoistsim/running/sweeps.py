"""Many runs through one compiled, vectorised call: sweeps of engagement force and the rest.

A sweep's runs go in blocks of consecutive runs (:mod:`hoistsim.running.blocks`), on
this process or spread over a Dask cluster (:mod:`hoistsim.running.cluster`); runs
that share a structure go through ``vmap`` of the restart loop a single run
uses, in chunks of a fixed width, so that memory stays bounded and one
compilation serves the whole sweep, and any later sweep of the same shape.
Finished blocks are written as they come (:mod:`hoistsim.running.streaming`).
"""

from __future__ import annotations

import contextlib
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from pathlib import Path

import jax
import numpy as np

from .. import _jax  # noqa: F401  (float64 before any array exists)
from ..errors import ScenarioError
from ..machine.assemble import build_plan, output_grid
from ..results.run_result import RunResult, Summaries
from ..results.run_summaries import summaries_of
from ..scenario.loading import Scenario
from ..scenario.sweep_runs import SweepRuns
from .blocks import chunk_for, run_blocks
from .simulation import read_layout
from .simulation import SimulationError

# Chunks in a block: the unit of work handed out (to a cluster's workers) and written (to a file's chunks).
# A summary-only block is one chunk: its host work (plans, summaries) overlaps the last block's compiled
# calls (blocks.run_blocks), so the smaller the block, the less of either is left without the other.
BLOCK_CHUNKS = 2
SUMMARY_BLOCK_CHUNKS = 1


@dataclass
class SweepResult:
    """The runs of a sweep, in sweep order; ``runs`` is None when only summaries were kept."""

    scenario: Scenario  # the scenario as given, sweep included
    labels: list[str]
    keys: list[str]  # swept keys
    parameters: dict[str, np.ndarray]  # swept key -> SI value of each run (NaN for tables)
    summaries: Summaries  # a dict per run when indexed, ``columns`` as arrays (read from the file when streamed)
    runs: list[RunResult] | None = None
    stats: dict = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)  # runs whose periodic regime did not settle, say

    def __len__(self) -> int:
        return len(self.labels)

    @property
    def summary(self) -> dict[str, np.ndarray]:
        """Column -> one value per run (labels included)."""
        return self.summaries.columns

    @cached_property
    def summary_units(self) -> dict[str, str]:
        """Units of every summary column, as the scene's elements declare them."""
        from .simulation import scene_summary_units

        return scene_summary_units(self.scenario)

    def to_hdf5(self, path, command: str = "") -> None:
        from ..results.output import write_sweep

        write_sweep(path, self, command=command)

    def to_xarray(self):
        """The sweep as one xarray.Dataset, as its file opens: series on (run, time), the swept keys and
        every summary value on (run), with units."""
        import xarray as xr

        from ..results.output import common_time
        from ..results.records import series_blocks
        from ..scenario.keys import key_units

        units = self.summary_units
        data = {"label": ("run", np.asarray(self.labels, dtype=object))}
        for key, values in self.parameters.items():
            data[key] = ("run", np.asarray(values, dtype=float), {"units": key_units(key)})
        for key, values in self.summary.items():
            if key != "label":
                data[key] = ("run", values, {"units": units.get(key, "")})
        coords = {"run": ("run", np.arange(len(self)))}
        if self.runs is not None:
            time, padded = common_time([run.grid for run in self.runs])
            stacked = series_blocks(self.runs, time, padded)
            coords["time"] = ("time", time, {"units": "s"})
            first = self.runs[0]
            for name, values in stacked.items():
                data[name] = (("run", "time"), values, {"units": first.units[name]})
        return xr.Dataset(data, coords=coords, attrs={"name": self.scenario.name,
                                                      "swept_keys": ", ".join(self.keys)})


def sweep(scenario: Scenario, *, summary_only: bool = False, chunk_size: int | None = None,
          progress: Callable[[int, int], None] | None = None, output=None, command: str = "",
          resume: bool = False, workers: int | None = None, scheduler: str | None = None) -> SweepResult:
    """Run every value of the scenario's sweep (one run if it has none), vectorised.

    With ``output`` (a path), the results file is written as the runs finish
    (:mod:`hoistsim.running.streaming`): memory stays at a block's worth, the result
    keeps the summaries only, and ``resume`` goes on from the blocks an
    interrupted run of the same sweep left in its partial file.  ``workers``
    (a local Dask cluster of that many processes) or ``scheduler`` (the address
    of a running one) spread the blocks over a cluster (:mod:`hoistsim.running.cluster`);
    the numbers are the same bits as on one process.
    """
    runs = SweepRuns(scenario)
    started = time.perf_counter()
    with contextlib.ExitStack() as stack:
        client = None
        if workers is not None or scheduler is not None:  # connected before the file is touched
            from .cluster import connect

            client = stack.enter_context(connect(workers, scheduler))
        summaries, outcome, warnings = _sweep(runs, client, summary_only=summary_only, chunk_size=chunk_size,
                                              progress=progress, output=output, command=command, resume=resume)
    return SweepResult(
        scenario=scenario,
        labels=runs.labels,
        keys=runs.keys,
        parameters=runs.parameters,
        summaries=summaries,
        runs=outcome,
        stats={"wall_time": time.perf_counter() - started, "runs": len(runs)},
        warnings=warnings,
    )


def _sweep(runs, client, *, summary_only, chunk_size, progress, output, command, resume):
    """The runs' summaries, RunResults (None when streamed or summary-only) and warnings."""
    scenario = runs.base
    warnings: list[str] = []
    stream = None
    chunk = chunk_size or chunk_for(runs.scenario(0), summary_only, len(runs))
    if output is not None:
        from .streaming import StreamedFile

        split = (chunk, jax.device_count()) if client is None else (chunk,)  # a cluster's workers: their own
        stream = StreamedFile(output, scenario, runs.labels, runs.parameters, summary_only=summary_only,
                              command=command, resume=resume, split=split)
        if stream.nothing_to_resume:
            warnings.append(f"{Path(output).name}: nothing was kept to resume (no {stream.folder.name}); "
                            "started afresh")
        if stream.discarded:
            warnings.append(f"{Path(output).name}: an interrupted sweep's {stream.discarded} chunk file(s) were "
                            "discarded (--resume keeps them)")
    try:
        outcome = simulate_many(runs, summary_only=summary_only, chunk_size=chunk, progress=progress,
                                warnings=warnings, sink=stream, skip_blocks=stream.blocks_done if stream else 0,
                                client=client)
        if stream is not None:
            stream.finish()
    except (SimulationError, ScenarioError):
        if stream is not None:
            stream.discard()  # a run that fails would fail again: nothing to resume
        raise
    except BaseException:
        if stream is not None:
            stream.close()  # interrupted: the finished blocks stay for --resume
        raise
    if stream is not None:  # read back from the file when asked for: memory does not grow with the runs
        from ..results.reading import FileSummaries

        plan, _ = build_plan(runs.scenario(0), summary_only=True)
        flags = [name for name, units in read_layout(plan, runs.scenario(0)).summaries.items() if units == "bool"]
        return FileSummaries(output, flags), None, warnings
    if summary_only:
        return outcome, None, warnings
    return summaries_of(outcome), outcome, warnings


class ListedRuns:
    """Runs given as a list of scenarios (a flywheel's candidates), read like :class:`SweepRuns`."""

    def __init__(self, scenarios: list[Scenario], labels: list[str]):
        self.scenarios, self.labels = scenarios, labels

    def __len__(self) -> int:
        return len(self.scenarios)

    def scenario(self, i: int) -> Scenario:
        return self.scenarios[i]

    def label(self, i: int) -> str:
        return self.labels[i]


def simulate_many(runs, labels: list[str] | None = None, *, summary_only: bool = False,
                  chunk_size: int | None = None, progress=None, warnings: list | None = None,
                  sink=None, skip_blocks: int = 0, client=None):
    """The runs' RunResults, or (``summary_only``) their :class:`Summaries`, in order.

    ``runs`` is a :class:`SweepRuns` or a list of scenarios (then ``labels``
    names them).  Runs go in blocks of consecutive runs, each a few chunks of
    the compiled loop's width (:func:`hoistsim.running.blocks.run_blocks`), on this process or spread
    over a Dask cluster (``client``, :mod:`hoistsim.running.cluster`); ``sink`` (:class:`hoistsim.running.streaming.StreamedFile`)
    takes each block as it finishes, in order, and nothing is kept (None is returned);
    the first ``skip_blocks`` blocks (a resumed sweep's, in the file already)
    are not run.  ``warnings`` collects what the runs warn of.
    """
    if not isinstance(runs, (SweepRuns, ListedRuns)):
        runs = ListedRuns(runs, labels)
    total = len(runs)
    chunk = chunk_size or chunk_for(runs.scenario(0), summary_only, total)
    size = chunk * (SUMMARY_BLOCK_CHUNKS if summary_only else BLOCK_CHUNKS)
    blocks = [(start, min(start + size, total)) for start in range(0, total, size)]
    if sink is not None:
        sink.begin(_grids(runs) if not summary_only else None)
    done = sum(stop - start for start, stop in blocks[:skip_blocks])
    todo = blocks[skip_blocks:]
    records = sink is not None  # a file's records wanted, not runs
    if client is not None:
        from .cluster import cluster_blocks

        finished = cluster_blocks(client, runs, todo, summary_only=summary_only, chunk=chunk, records=records)
    else:
        finished = run_blocks(runs, todo, summary_only=summary_only, chunk=chunk, records=records)
    kept: list = []
    for block in finished:
        if warnings is not None:
            warnings.extend(block.warnings)
        if sink is not None:
            sink.write(block)  # written: nothing of it is kept here
        else:
            kept.append(block.outcome)
        done += block.stop - block.start
        if progress is not None:
            progress(done, total)
    if sink is not None:
        return None
    if summary_only:
        return Summaries.concatenate(kept)
    return [run for part in kept for run in part]


def _grids(runs) -> list[np.ndarray]:
    """Every run's output grid (the common time axis of a full-output file is made of them)."""
    keys = getattr(runs, "keys", None)
    if keys is not None and not any(key.startswith("simulation.") for key in keys):
        sim = runs.scenario(0).simulation  # no swept key moves the grid: one for all
        grid = output_grid(sim.duration, sim.output_interval)
        return [grid] * len(runs)
    return [output_grid(s.simulation.duration, s.simulation.output_interval)
            for s in (runs.scenario(i) for i in range(len(runs)))]

"""Many runs through one compiled, vectorised call: sweeps of engagement force and the rest.

Runs that share a structure (solver, output grid, effects, force-table length
after padding) are stacked and sent through ``vmap`` of the same restart loop
a single run uses, in chunks of a fixed size so that memory stays bounded and
one compilation serves the whole sweep, and any later sweep of the same shape.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import gc
import math
import time
from pathlib import Path
from collections.abc import Callable
from dataclasses import dataclass, field

import jax
import numpy as np

from . import _jax
from .assemble import build_plan, loop_sizes, output_grid
from .core.loop import OK, SOLVERS, Plan, _run
from .core.readout import STATUS, BatchReadout, Readout
from .periodic.analysis import periodic_regime
from .results import RunResult, Summaries, summary_columns
from .scenario import Scenario
from .simulation import SimulationError, failure_message, run_result, simulate
from .sweep_runs import SweepRuns

# Bytes of time series a chunk may hold.  Measured: with full output, small
# chunks are fastest per run (every segment rewrites the chunk's output arrays);
# summary-only runs hold one row each and go 1024 at a time.
CHUNK_BYTES = 4 * 2**20
MAX_CHUNK = 1024

# Chunks in a block: the unit of work handed out (to a cluster's workers) and written (to a file's chunks).
BLOCK_CHUNKS = 2
# A vmapped chunk steps until its slowest run is done: runs of a block go into chunks in the order of their
# swept values, so that runs of like work share a chunk (benchmarks/sweep.py measures what it gains).
ORDER_BY_SWEPT_VALUE = True


@dataclass
class SweepResult:
    """The runs of a sweep, in sweep order; ``runs`` is None when only summaries were kept."""

    scenario: Scenario  # the scenario as given, sweep included
    labels: list[str]
    keys: list[str]  # swept keys
    parameters: dict[str, np.ndarray]  # swept key -> SI value of each run (NaN for tables)
    summaries: Summaries  # a dict per run when indexed; its ``columns`` keep them as arrays
    runs: list[RunResult] | None = None
    stats: dict = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)  # runs whose periodic regime did not settle, say

    def __len__(self) -> int:
        return len(self.labels)

    @property
    def summary(self) -> dict[str, np.ndarray]:
        """Column -> one value per run (labels included)."""
        return self.summaries.columns

    def to_hdf5(self, path, command: str = "") -> None:
        from .output import write_sweep

        write_sweep(path, self, command=command)

    def to_xarray(self):
        """The sweep as one xarray.Dataset, as its file opens: series on (run, time), the swept keys and
        every summary value on (run), with units."""
        import xarray as xr

        from .output import _summary_units, common_time, series_blocks
        from .scenario import key_units

        units = _summary_units(self.scenario)
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
    (:mod:`hoistsim.streaming`): memory stays at a block's worth, the result
    keeps the summaries only, and ``resume`` goes on from the blocks an
    interrupted run of the same sweep left in its partial file.  ``workers``
    (a local Dask cluster of that many processes) or ``scheduler`` (the address
    of a running one) spread the blocks over a cluster (:mod:`hoistsim.cluster`);
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
    if output is not None:
        from .streaming import StreamedFile

        stream = StreamedFile(output, scenario, runs.labels, runs.parameters, summary_only=summary_only,
                              command=command, resume=resume)
        if stream.discarded:
            warnings.append(f"{Path(output).name}: an interrupted sweep's {stream.discarded} chunk file(s) were "
                            "discarded (--resume keeps them)")
    try:
        outcome = simulate_many(runs, summary_only=summary_only, chunk_size=chunk_size, progress=progress,
                                warnings=warnings, sink=stream, skip_blocks=stream.blocks_done if stream else 0,
                                client=client)
        if stream is not None:
            outcome = stream.finish(outcome)
    except SimulationError:
        if stream is not None:
            stream.discard()  # a run that fails would fail again: nothing to resume
        raise
    except BaseException:
        if stream is not None:
            stream.close()  # interrupted: the finished blocks stay for --resume
        raise
    if summary_only or stream is not None:
        return outcome, None, warnings
    return Summaries.from_rows([run.summary for run in outcome]), outcome, warnings


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


@dataclass
class Block:
    """The outcome of the runs ``start`` to ``stop``: their summaries, or (full output) their RunResults."""

    start: int
    stop: int
    outcome: object  # Summaries, or a list of RunResult
    warnings: list


def simulate_many(runs, labels: list[str] | None = None, *, summary_only: bool = False,
                  chunk_size: int | None = None, progress=None, warnings: list | None = None,
                  sink=None, skip_blocks: int = 0, client=None):
    """The runs' RunResults, or (``summary_only``) their :class:`Summaries`, in order.

    ``runs`` is a :class:`SweepRuns` or a list of scenarios (then ``labels``
    names them).  Runs go in blocks of consecutive runs, each a few chunks of
    the compiled loop's width (:func:`run_block`), on this process or spread
    over a Dask cluster (``client``, :mod:`hoistsim.cluster`); ``sink`` (:class:`hoistsim.streaming.StreamedFile`)
    takes each block as it finishes, in order, and only summaries are kept;
    the first ``skip_blocks`` blocks (a resumed sweep's, in the file already)
    are not run and their entries stay None.  ``warnings`` collects what the
    runs warn of.
    """
    if not isinstance(runs, (SweepRuns, ListedRuns)):
        runs = ListedRuns(runs, labels)
    total = len(runs)
    chunk = chunk_size or _chunk_for(runs.scenario(0), summary_only, total)
    size = chunk * BLOCK_CHUNKS
    blocks = [(start, min(start + size, total)) for start in range(0, total, size)]
    if sink is not None:
        sink.begin(_grids(runs) if not summary_only else None)
    done = sum(stop - start for start, stop in blocks[:skip_blocks])
    todo = blocks[skip_blocks:]
    if client is not None:
        from .cluster import cluster_blocks

        finished = cluster_blocks(client, runs, todo, summary_only=summary_only, chunk=chunk)
    else:
        finished = (run_block(runs, start, stop, summary_only=summary_only, chunk=chunk) for start, stop in todo)
    kept: list = []
    for block in finished:
        if warnings is not None:
            warnings.extend(block.warnings)
        if sink is not None:
            sink.write(block)
        kept.append(block.outcome if summary_only or sink is None else
                    Summaries.from_rows([run.summary for run in block.outcome]))
        done += block.stop - block.start
        if progress is not None:
            progress(done, total)
    if sink is not None or summary_only:
        return Summaries.concatenate(kept) if kept else None
    return [run for part in kept for run in part]


def run_block(runs, start: int, stop: int, *, summary_only: bool, chunk: int) -> Block:
    """Runs ``start`` to ``stop``: their scenarios and plans built here, grouped by the compiled loop they
    share, each group in chunks of ``chunk`` runs through one vmapped call (padded to a full chunk)."""
    with _no_cyclic_collection():
        return _run_block(runs, start, stop, summary_only=summary_only, chunk=chunk)


@contextlib.contextmanager
def _no_cyclic_collection():
    """The cyclic garbage collector off while a block's host objects are built: measured, its passes over
    the thousands of scenarios and plans alive cost 50 us a run (40 % of a summary-only sweep); the
    block's objects form no cycles, so reference counting frees them."""
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


def _run_block(runs, start: int, stop: int, *, summary_only: bool, chunk: int) -> Block:
    indices = range(start, stop)
    scenarios = [runs.scenario(i) for i in indices]
    plans = [build_plan(s, summary_only=summary_only) for s in scenarios]
    warnings: list[str] = []
    rows: list = [None] * len(scenarios)  # each run's RunResult, or its chunk's summary columns and lane
    parts: list = []
    for group in _groups(scenarios, plans):
        group = _by_swept_value(runs, start, group)
        group_plans = _padded_tables([plans[k][0] for k in group])
        first = scenarios[group[0]]
        max_switches = max(scenarios[k].simulation.max_switches for k in group)
        sizes = tuple(max(n) for n in zip(*(loop_sizes(plan, max_switches) for plan in group_plans)))
        periodic = any(e.cycles for e in group_plans[0].elements)
        lean = summary_only and not periodic
        if lean:  # the summary needs no event rows, only their counts
            sizes = (sizes[0], 1)
        layout = group_plans[0].layout
        run, built = None, None
        for offset in range(0, len(group), chunk):
            part = group[offset:offset + chunk]
            batch = group_plans[offset:offset + chunk]
            batch = batch + [batch[-1]] * (chunk - len(batch))  # a full chunk: one compiled shape
            stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *batch)
            while True:
                if built != sizes:
                    run = _jax.executable(compiled_batch(first.simulation.solver, *sizes, not lean), stacked,
                                          name=f"sweep-{first.simulation.solver}-{sizes}-{lean}")
                    built = sizes
                t0 = time.perf_counter()
                raw = jax.device_get(run(stacked))
                elapsed = (time.perf_counter() - t0) / len(part)
                logged = int(np.max(raw.counters[: len(part), 0]))
                if lean or logged <= sizes[1]:
                    break
                sizes = loop_sizes(group_plans[0], max_switches, log_size=logged + 1)  # room for every row
            _check_status(runs, scenarios, part, start, layout, raw, lean)
            if not summary_only:
                for k, lane in enumerate(part):
                    one = Readout(layout, raw, lane=k)
                    rows[lane] = run_result(scenarios[lane], runs.label(start + lane), plans[lane][1], one, elapsed)
                    warnings.extend(rows[lane].warnings)
                continue
            labels = [runs.label(start + lane) or scenarios[lane].name for lane in part]
            batch_read = BatchReadout(layout, raw, len(part))
            values = batch_read.summary()
            if periodic:
                extra = _periodic_values(scenarios, part, layout, raw, labels, warnings)
                values.update(extra)
            columns = summary_columns(labels, values, batch_read.ledger(), batch_read.count("lock"),
                                      batch_read.count("unlock"))
            parts.append((np.asarray(part), columns))
    if summary_only:
        return Block(start, stop, _in_order(parts, len(scenarios)), warnings)
    return Block(start, stop, rows, warnings)


def _by_swept_value(runs, start: int, group: list[int]) -> list[int]:
    """The block's runs ``group`` in the order of their swept values (the first key first; tables, which
    have no one value, stay as they are)."""
    if not ORDER_BY_SWEPT_VALUE or not getattr(runs, "keys", None):
        return group
    rows = np.asarray(group) + start
    values = [runs.parameters[key][rows] for key in reversed(runs.keys)]
    if all(np.isnan(v).all() for v in values):
        return group
    return [group[k] for k in np.lexsort(values)]


def _in_order(parts, count: int) -> Summaries:
    """Summary columns of each group's chunks, back in the runs' order."""
    order = np.concatenate([lanes for lanes, _ in parts])
    place = np.empty(count, dtype=np.int64)
    place[order] = np.arange(count)
    keys = parts[0][1].keys()
    return Summaries({key: np.concatenate([columns[key] for _, columns in parts])[place] for key in keys})


def _periodic_values(scenarios, part, layout, raw, labels, warnings) -> dict[str, np.ndarray]:
    """The periodic regime of each run of a chunk, read from its event rows: name -> values."""
    rows = []
    for k, lane in enumerate(part):
        regime = periodic_regime(scenarios[lane], Readout(layout, raw, lane=k))
        rows.append(regime.values())
        if not regime.regime.settled:
            warnings.append(f"{labels[k]}: {regime.regime.message}")
    return {key: np.asarray([row[key] for row in rows]) for key in rows[0]}


def _check_status(runs, scenarios, part, start, layout, raw, lean) -> None:
    """A run of the chunk that failed (chattering, the solver) fails the sweep, saying which and why."""
    failed = np.flatnonzero(raw.counters[: len(part), STATUS] != OK)
    if failed.size == 0:
        return
    k = int(failed[0])
    lane = part[k]
    scenario, name = scenarios[lane], runs.label(start + lane) or scenarios[lane].name
    if lean:  # the lean run kept no event rows: run it alone to say what happened
        try:
            simulate(scenario)
        except SimulationError as exc:
            raise SimulationError(f"{name}: {exc}") from None
    raise SimulationError(f"{name}: " + failure_message(scenario, Readout(layout, raw, lane=k)))


def _grids(runs) -> list[np.ndarray]:
    """Every run's output grid (the common time axis of a full-output file is made of them)."""
    keys = getattr(runs, "keys", None)
    if keys is not None and not any(key.startswith("simulation.") for key in keys):
        sim = runs.scenario(0).simulation  # no swept key moves the grid: one for all
        grid = output_grid(sim.duration, sim.output_interval)
        return [grid] * len(runs)
    return [output_grid(s.simulation.duration, s.simulation.output_interval)
            for s in (runs.scenario(i) for i in range(len(runs)))]


def _groups(scenarios, plans) -> list[list[int]]:
    """Runs that can share one compiled loop: same solver, effects and grid."""
    groups: dict = {}
    for i, (scenario, (plan, grid)) in enumerate(zip(scenarios, plans)):
        structure = jax.tree.structure(plan.elements)
        key = (scenario.simulation.solver, structure, np.asarray(plan.grid).tobytes())
        groups.setdefault(key, []).append(i)
    return list(groups.values())


def _padded_tables(plans: list[Plan]) -> list[Plan]:
    """Every element's tables padded to the longest in the group (one compiled shape).

    A table's last row is repeated, and the duration added as a boundary for
    each row added, so every run keeps its own values and boundaries.
    """
    longest: dict = {}
    for plan in plans:
        for i, element in enumerate(plan.elements):
            for name, (times, _) in element.tables().items():
                longest[i, name] = max(longest.get((i, name), 0), int(getattr(element, times).shape[0]))
    out = []
    for plan in plans:
        elements, extra_boundaries = list(plan.elements), 0
        for i, element in enumerate(plan.elements):
            changes = {}
            for name, fields in element.tables().items():
                extra = longest[i, name] - int(getattr(element, fields[0]).shape[0])
                if extra:
                    for f in fields:
                        column = getattr(element, f)
                        changes[f] = np.concatenate([column, np.full(extra, column[-1])])
                    extra_boundaries += extra
            if changes:
                elements[i] = dataclasses.replace(element, **changes)
        if extra_boundaries:
            boundaries = np.concatenate([plan.boundaries, np.full(extra_boundaries, plan.duration)])
            plan = dataclasses.replace(plan, elements=tuple(elements), boundaries=boundaries)
        out.append(plan)
    return out


def _chunk_for(scenario: Scenario, summary_only: bool, runs: int) -> int:
    """Runs per vmapped call: as many as CHUNK_BYTES of time series allow (at most MAX_CHUNK), a power of
    two (few compiled shapes), no more than the sweep needs."""
    plan, _ = build_plan(scenario, summary_only=summary_only)
    rows, states = int(plan.grid.shape[0]), plan.layout.size
    per_run = rows * 8 * (2 * states + 24)  # states, outputs and masks of one run
    chunk = max(1, min(MAX_CHUNK, CHUNK_BYTES // per_run))
    chunk = 1 << int(math.log2(chunk))
    return min(chunk, 1 << math.ceil(math.log2(runs)))


@functools.lru_cache(maxsize=None)
def compiled_batch(solver_name: str, max_segments: int, log_size: int, columns: bool = True):
    """The restart loop, vectorised over a leading batch axis of the plan (without columns: summaries only)."""
    solver = SOLVERS[solver_name]()
    return jax.jit(jax.vmap(functools.partial(_run, solver=solver, max_segments=max_segments, log_size=log_size,
                                              columns=columns)))

"""A block of a sweep's runs: built, run through the compiled vectorised loop a chunk at a time, read back.

A block is a range of consecutive runs, the unit a sweep hands out (to this
process or a cluster's workers) and writes.  Its runs' scenarios and plans are
made here; runs that share a compiled loop (solver, effects, grid) go
together, in chunks of a fixed width (padded to it: one compiled shape), in
the order of their swept values; summaries are read for a whole chunk at once.
"""

from __future__ import annotations

import contextlib
import dataclasses
import functools
import gc
import math
import time
from dataclasses import dataclass

import jax
import numpy as np
from jax.sharding import Mesh, NamedSharding, PartitionSpec

from .. import _jax
from ..errors import ScenarioError
from ..machine.assemble import build_plan, log_rows, step_room
from ..machine.core.loop import SOLVERS, restart_loop
from ..machine.core.plan import OK, Plan
from ..machine.core.schedule import scheduled_times
from ..machine.core.readout import EVENT_COUNT, KEPT_STEPS, STATUS, BatchReadout, Readout
from ..results.periodic.analysis import periodic_regime
from ..results.chunk_records import chunk_record
from ..results.records import joined
from ..results.run_result import Summaries
from ..results.run_summaries import summary_columns
from ..scenario.loading import Scenario
from .block_plans import block_plans, padded
from .simulation import SimulationError, failure_message, read_layout, run_result, scenario_errors, simulate

# Bytes of time series a chunk may hold on each device it is split over.  Measured: with full output,
# small chunks are fastest per run; summary-only runs hold one row each and go 2048 a device at a time
# (per run, on 2 cores and 2 devices, 8 192 runs of the stepped force sweep of benchmarks/engine_cost.py:
# 26.9 us at 1 024 a chunk, 20.9 at 2 048, 18.8 at 4 096, 20.3 at 8 192; the direct start 15.0, 11.5, 9.9, 10.1).
CHUNK_BYTES = 4 * 2**20
MAX_CHUNK = 2048
# A vmapped chunk steps until its slowest run is done: runs of a block go into chunks in the order of their
# swept values, so that runs of like work share a chunk (benchmarks/sweep.py measures what it gains).
ORDER_BY_SWEPT_VALUE = True


@dataclass
class Block:
    """The outcome of the runs ``start`` to ``stop``: their summaries, or (full output) their RunResults."""

    start: int
    stop: int
    outcome: object  # Summaries, or a list of RunResult
    warnings: list


def run_block(runs, start: int, stop: int, *, summary_only: bool, chunk: int, devices: int | None = None,
              records: bool = False) -> Block:
    """Runs ``start`` to ``stop``: their scenarios and plans built here, grouped by the compiled loop they
    share, each group in chunks of ``chunk`` runs through one vmapped call (padded to a full chunk), split
    over ``devices`` (None: :func:`devices_for` the chunk; a cluster's worker is told the client's).
    ``records``: full output as a results file's record where the block's runs allow (:func:`_block_steps`)."""
    with _no_cyclic_collection():
        return _run_block(runs, start, stop, summary_only=summary_only, chunk=chunk, devices=devices,
                          records=records)


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


def _run_block(runs, start: int, stop: int, *, summary_only: bool, chunk: int, devices: int | None,
               records: bool) -> Block:
    steps = _block_steps(runs, start, stop, summary_only=summary_only, chunk=chunk, devices=devices,
                         records=records)
    next(steps)
    return _finished(steps)


def _finished(steps) -> Block:
    """The block of a :func:`_block_steps` that has launched its runs, once they are done."""
    try:
        next(steps)
    except StopIteration as done:
        return done.value
    raise RuntimeError("a block's steps yield once")


def run_blocks(runs, blocks, *, summary_only: bool, chunk: int, records: bool = False):
    """Blocks ``(start, stop)`` in order, each built and launched while the one before computes: the
    compiled calls run on their own threads, so the host's work for the next block (its plans) costs
    no wall time while there are runs to wait for.  ``records``: full output as a results file's record
    where a block's runs allow (:func:`_block_steps`)."""
    waiting = None
    with _no_cyclic_collection():
        for start, stop in blocks:
            steps = _block_steps(runs, start, stop, summary_only=summary_only, chunk=chunk, devices=None,
                                 records=records)
            next(steps)
            if waiting is not None:
                yield _finished(waiting)
            waiting = steps
        if waiting is not None:
            yield _finished(waiting)


def _block_steps(runs, start: int, stop: int, *, summary_only: bool, chunk: int, devices: int | None,
                 records: bool = False):
    """A block's runs: built, their compiled calls launched (summary-only: all of them, not waited for),
    one ``yield``, then read back; returns the :class:`Block`.  Full output is a RunResult a run, or with
    ``records`` (a file's records wanted, not runs) where the block's plans come from its first run's and
    have no periodic regime, the block's record read straight from its chunks' arrays
    (:func:`hoistsim.results.chunk_records.chunk_record`)."""
    indices = range(start, stop)
    scenarios = LazyScenarios(runs, start)
    # the plans from the block's first run's (block_plans) where that applies, else each built in full
    fast = block_plans(runs, list(indices), summary_only=summary_only)
    if fast is not None:
        plans, groups = None, [list(range(len(indices)))]
    else:
        plans = [build_plan(scenarios[k], summary_only=summary_only) for k in range(len(indices))]
        groups = _groups(scenarios, plans)
    devices = devices or devices_for(chunk)
    launched = [_launch(runs, scenarios, group, plans, fast, summary_only, chunk, devices, start)
                for group in groups]
    yield
    warnings: list[str] = []
    rows: list = [None] * len(indices)  # each run's RunResult, or its chunk's summary columns and lane
    parts: list = []
    kept: list = []  # the chunks' records
    for group in launched:
        layout, lean, periodic = group["layout"], group["lean"], group["periodic"]
        for part, raw, elapsed in _results(group):
            check_status(runs, scenarios, part, start, layout, raw, lean)
            if records and not summary_only and fast is not None and not periodic:
                kept.append(chunk_record(layout, raw, len(part), fast.grid, np.asarray(part) + start,
                                         _labels(runs, scenarios, start, part), elapsed))
                continue
            if not summary_only:
                for k, lane in enumerate(part):
                    one = Readout(layout, raw, lane=k)
                    grid = fast.grid if fast is not None else plans[lane][1]
                    rows[lane] = run_result(scenarios[lane], runs.label(start + lane), grid, one, elapsed)
                    warnings.extend(rows[lane].warnings)
                continue
            labels = _labels(runs, scenarios, start, part)
            batch_read = BatchReadout(layout, raw, len(part))
            values = batch_read.summary()
            if periodic:
                extra = _periodic_values(scenarios, part, layout, raw, labels, warnings)
                values.update(extra)
            columns = summary_columns(labels, values, batch_read.ledger(), batch_read.count("lock"),
                                      batch_read.count("unlock"))
            parts.append((np.asarray(part), columns))
    if summary_only:
        return Block(start, stop, in_order(parts, len(indices)), warnings)
    if kept:
        return Block(start, stop, joined(kept), warnings)
    return Block(start, stop, rows, warnings)


def _launch(runs, scenarios, group, plans, fast, summary_only: bool, chunk: int, devices: int, start: int) -> dict:
    """A group's chunks stacked and their compiled loop found; summary-only, every chunk's call launched
    (full output calls are made as they are read: a chunk may need a longer event log)."""
    group = _by_swept_value(runs, start, group)
    group_plans = [fast.plan(0)] if fast is not None else _padded_tables([plans[k][0] for k in group])
    first = scenarios[group[0]]
    periodic = any(e.cycles for e in group_plans[0].elements)
    if fast is not None and not periodic:  # one structure and simulation: every plan's rows are the first's
        rows = log_rows(group_plans[0])
    elif fast is not None:
        rows = max(log_rows(fast.plan(r)) for r in group)
    else:
        rows = max(log_rows(plan) for plan in group_plans)
    lean = summary_only and not periodic
    # the summary needs no event rows, only their counts, and no steps; else room for the steps of the rows
    sizes = (1, 1) if lean else (rows, step_room(group_plans[0], sweep=True))
    chunks = []
    for offset in range(0, len(group), chunk):
        part = group[offset:offset + chunk]
        lanes = part + [part[-1]] * (chunk - len(part))  # a full chunk: one compiled shape
        if fast is not None:
            stacked = fast.stacked(lanes)
        else:
            batch = group_plans[offset:offset + chunk]
            stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *batch + [batch[-1]] * (chunk - len(batch)))
        chunks.append((part, stacked))
    solver = first.simulation.solver
    run = _jax.executable(functools.partial(compiled_batch, solver, *sizes, not lean, devices), chunks[0][1],
                          name=f"sweep-{solver}-{sizes}-{lean}", devices=devices)
    # launched, not waited for: the host goes on while they run
    calls = [(time.perf_counter(), run(stacked)) if lean else None for _, stacked in chunks]
    return dict(chunks=chunks, calls=calls, run=run, sizes=sizes, lean=lean, periodic=periodic, solver=solver,
                devices=devices, layout=read_layout(group_plans[0], first), first_plan=group_plans[0])


def _results(group: dict):
    """(runs of the chunk, what the compiled loop returned, seconds per run) for each of a group's chunks."""
    run, sizes, built = group["run"], group["sizes"], group["sizes"]
    for (part, stacked), call in zip(group["chunks"], group["calls"]):
        while True:
            if built != sizes:
                run = _jax.executable(functools.partial(compiled_batch, group["solver"], *sizes, True,
                                                        group["devices"]),
                                      stacked, name=f"sweep-{group['solver']}-{sizes}-False", devices=group["devices"])
                built = sizes
            started, pending = call if call is not None else (time.perf_counter(), run(stacked))
            raw = jax.device_get(pending)
            elapsed = (time.perf_counter() - started) / len(part)
            logged = int(np.max(raw.counters[: len(part), EVENT_COUNT]))
            kept = int(np.max(raw.counters[: len(part), KEPT_STEPS]))
            if group["lean"] or (logged <= sizes[0] and kept <= sizes[1]):
                break
            call = None
            # room for every event row and every step
            first = group["first_plan"]
            sizes = (log_rows(first, log_size=logged + 1), step_room(first, kept, sweep=True))
        yield part, raw, elapsed


def _labels(runs, scenarios, start: int, part: list[int]):
    """The labels of a block's runs ``part`` (a run without one: its scenario's name)."""
    if getattr(runs, "keys", None):  # a sweep's: made from its values' labels, all at once
        return runs.labels_of(np.asarray(part) + start)
    return [runs.label(start + lane) or scenarios[lane].name for lane in part]


class LazyScenarios:
    """The scenarios of a block's runs, each built when first asked for (a summary-only sweep asks for few)."""

    def __init__(self, runs, start: int = 0):
        self.runs, self.start, self.built = runs, start, {}

    def __getitem__(self, k: int):
        if k not in self.built:
            self.built[k] = self.runs.scenario(self.start + k)
        return self.built[k]

    def __iter__(self):
        raise TypeError("index the block's scenarios: iterating would build them all")


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


def in_order(parts, count: int) -> Summaries:
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


def check_status(runs, scenarios, part, start, layout, raw, lean) -> None:
    """A run of the chunk that crossed a limit saying its scenario is wrong (an element's ``errors``), or
    that failed (chattering, the solver), fails the sweep, saying which run and why."""
    _check_errors(runs, scenarios, part, start, layout, raw, lean)
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


def _check_errors(runs, scenarios, part, start, layout, raw, lean) -> None:
    """The first run of the chunk that crossed an element's error limit raises its one-line ScenarioError."""
    kinds = [layout.name(kind) for element in layout.elements for kind in element.errors
             if layout.name(kind) in layout.event_kinds]
    if not kinds:
        return
    counts = np.asarray(raw.kind_counts[: len(part)])[:, [layout.kind_code(kind) for kind in kinds]]
    crossed = np.flatnonzero(counts.sum(axis=1) > 0)
    if crossed.size == 0:
        return
    k = int(crossed[0])
    lane = part[k]
    scenario, name = scenarios[lane], runs.label(start + lane) or scenarios[lane].name
    try:
        if lean:  # the lean run kept no event rows, so no time: run it alone
            simulate(scenario)
        else:
            scenario_errors(scenario, Readout(layout, raw, lane=k))
    except ScenarioError as exc:
        raise ScenarioError(exc.key, f"{exc.message} (run {name})", source=exc.source, line=exc.line) from None


def _groups(scenarios, plans) -> list[list[int]]:
    """Runs that can share one compiled loop: same solver, effects and grid."""
    groups: dict = {}
    for i, (plan, grid) in enumerate(plans):
        structure = jax.tree.structure(plan.elements)
        key = (scenarios[i].simulation.solver, structure, np.asarray(plan.grid).tobytes())
        groups.setdefault(key, []).append(i)
    return list(groups.values())


def _padded_tables(plans: list[Plan]) -> list[Plan]:
    """Every element's tables padded to the longest in the group (one compiled shape).

    A table's last row is repeated (:func:`hoistsim.running.block_plans.padded`), and the duration added as a
    boundary for each boundary the padded elements schedule beyond their own (a row added, and whatever an
    element schedules for it: a clutch's force table its zero crossings), so every run keeps its own values
    and boundaries.
    """
    columns = [padded([plan.elements[k] for plan in plans]) for k in range(len(plans[0].elements))]
    out = []
    for r, plan in enumerate(plans):
        elements = tuple(column[r] for column in columns)
        extra = len(scheduled_times(elements)) - len(scheduled_times(plan.elements))
        if extra:
            boundaries = np.concatenate([plan.boundaries, np.full(extra, plan.duration)])
            plan = dataclasses.replace(plan, elements=elements, boundaries=boundaries)
        out.append(plan)
    return out


def chunk_for(scenario: Scenario, summary_only: bool, runs: int) -> int:
    """Runs per vmapped call: on each device, as many as CHUNK_BYTES of time series allow (at most
    MAX_CHUNK), a power of two (few compiled shapes), no more than the sweep needs; times the devices."""
    plan, _ = build_plan(scenario, summary_only=summary_only)
    rows, states = int(plan.grid.shape[0]), plan.layout.size
    per_run = rows * 8 * (2 * states + 24)  # states, outputs and masks of one run
    per_device = 1 << int(math.log2(max(1, min(MAX_CHUNK, CHUNK_BYTES // per_run))))
    devices = len(jax.devices())
    if runs < devices:  # fewer runs than devices: split over as many as divide the chunk
        return min(per_device, 1 << math.ceil(math.log2(runs)))
    return devices * min(per_device, 1 << math.ceil(math.log2(math.ceil(runs / devices))))


def devices_for(chunk: int) -> int:
    """Devices a chunk's runs are split over: the most there are that divide it evenly."""
    return max(d for d in range(1, min(len(jax.devices()), chunk) + 1) if chunk % d == 0)



@functools.lru_cache(maxsize=None)
def compiled_batch(solver_name: str, log_size: int, step_room: int, columns: bool = True, devices: int = 1):
    """The restart loop, vectorised over a leading batch axis of the plan (without columns: summaries only).

    With several ``devices``, each runs its share of the batch's runs through its
    own loop (``shard_map``): a device's loop steps until its slowest run is
    done, never waiting for the others'.
    """
    solver = SOLVERS[solver_name]()
    return over_devices(jax.vmap(functools.partial(restart_loop, solver=solver, log_size=log_size,
                                                   step_room=step_room, columns=columns, lanes=True)), devices)


def over_devices(batch, devices: int):
    """``batch`` (a function vmapped over a leading axis of runs) jitted, its runs split over ``devices``: each
    device runs its share through its own loop (``shard_map``), stepping until its slowest run is done."""
    if devices == 1:
        return jax.jit(batch)
    mesh = Mesh(np.array(jax.devices()[:devices]), ("runs",))
    split = NamedSharding(mesh, PartitionSpec("runs"))
    return jax.jit(jax.shard_map(batch, mesh=mesh, in_specs=PartitionSpec("runs"), out_specs=PartitionSpec("runs"),
                                 check_vma=False), in_shardings=split, out_shardings=split)

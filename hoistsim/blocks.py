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

from . import _jax
from .assemble import build_plan, loop_sizes
from .core.loop import OK, SOLVERS, Plan, _run
from .core.readout import STATUS, BatchReadout, Readout
from .periodic.analysis import periodic_regime
from .results import Summaries, summary_columns
from .scenario import Scenario
from .simulation import SimulationError, failure_message, run_result, simulate

# Bytes of time series a chunk may hold.  Measured: with full output, small
# chunks are fastest per run (every segment rewrites the chunk's output arrays);
# summary-only runs hold one row each and go 1024 at a time.
CHUNK_BYTES = 4 * 2**20
MAX_CHUNK = 1024
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


def chunk_for(scenario: Scenario, summary_only: bool, runs: int) -> int:
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

"""Many runs through one compiled, vectorised call: sweeps of engagement force and the rest.

Runs that share a structure (solver, output grid, effects, force-table length
after padding) are stacked and sent through ``vmap`` of the same restart loop
a single run uses, in chunks of a fixed size so that memory stays bounded and
one compilation serves the whole sweep, and any later sweep of the same shape.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Callable
from dataclasses import dataclass, field

import jax
import numpy as np

from . import _jax
from . import clutch_modes as cm
from .hybrid import OK, SOLVERS, Plan, _run
from .results import RunResult, summarize
from .scenario import Scenario, sweep_values
from .simulation import (
    SimulationError,
    _failure_message,
    _result,
    build_plan,
    loop_sizes,
)

# Bytes of time series a chunk may hold.  Measured: with full output, small
# chunks are fastest per run (every segment rewrites the chunk's output arrays);
# summary-only runs hold one row each and go 1024 at a time.
CHUNK_BYTES = 4 * 2**20
MAX_CHUNK = 1024

@dataclass
class SweepResult:
    """The runs of a sweep, in sweep order; ``runs`` is None when only summaries were kept."""

    scenario: Scenario  # the scenario as given, sweep included
    labels: list[str]
    keys: list[str]  # swept keys
    parameters: dict[str, np.ndarray]  # swept key -> SI value of each run (NaN for tables)
    summaries: list[dict]
    runs: list[RunResult] | None = None
    stats: dict = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.labels)

    @property
    def summary(self) -> dict[str, np.ndarray]:
        """Column -> one value per run (labels included)."""
        return {key: np.asarray([row[key] for row in self.summaries]) for key in self.summaries[0]}

    def to_hdf5(self, path, command: str = "") -> None:
        from .output import write_sweep

        write_sweep(path, self, command=command)


def sweep(scenario: Scenario, *, summary_only: bool = False, chunk_size: int | None = None,
          progress: Callable[[int, int], None] | None = None) -> SweepResult:
    """Run every value of the scenario's sweep (one run if it has none), vectorised."""
    pairs = sweep_values(scenario)
    labels = [label for label, _ in pairs]
    scenarios = [one for _, one in pairs]
    keys = list(scenario.sweep or {})
    started = time.perf_counter()
    outcome = simulate_many(scenarios, labels, summary_only=summary_only, chunk_size=chunk_size,
                            progress=progress)
    runs = None if summary_only else outcome
    summaries = outcome if summary_only else [run.summary for run in outcome]
    return SweepResult(
        scenario=scenario,
        labels=labels,
        keys=keys,
        parameters={key: np.asarray([swept_number(one, key) for one in scenarios]) for key in keys},
        summaries=summaries,
        runs=runs,
        stats={"wall_time": time.perf_counter() - started, "runs": len(labels)},
    )


def swept_number(scenario: Scenario, key: str) -> float:
    """The SI value of a swept key in one run (a constant force table counts as its force)."""
    value = scenario
    for part in key.split("."):
        value = getattr(value, part)
    if hasattr(value, "forces"):
        return value.forces[0] if len(set(value.forces)) == 1 else math.nan
    return float(value) if isinstance(value, (int, float)) else math.nan


def simulate_many(scenarios: list[Scenario], labels: list[str], *, summary_only: bool = False,
                  chunk_size: int | None = None, progress=None) -> list:
    """RunResults (or, with ``summary_only``, summary dicts) for many scenarios, in their order."""
    plans = [build_plan(s, summary_only=summary_only) for s in scenarios]
    out: list = [None] * len(scenarios)
    done = 0
    for indices in _groups(scenarios, plans):
        group = [plans[i][0] for i in indices]
        table_length = max(int(p.force_times.shape[0]) for p in group)
        group = [_pad_table(p, table_length) for p in group]
        first = scenarios[indices[0]]
        max_switches = max(scenarios[i].simulation.max_switches for i in indices)
        sizes = loop_sizes(group[0], max_switches)
        rows = int(group[0].grid.shape[0])
        chunk = chunk_size or _chunk_for(rows, len(indices))
        run = None
        for start in range(0, len(indices), chunk):
            part = indices[start:start + chunk]
            batch = group[start:start + chunk]
            batch = batch + [batch[-1]] * (chunk - len(batch))  # a full chunk: one compiled shape
            stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *batch)
            if run is None:
                run = _jax.executable(compiled_batch(first.simulation.solver, *sizes), stacked,
                                      name=f"sweep-{first.simulation.solver}-{sizes}")
            t0 = time.perf_counter()
            raw = jax.device_get(run(stacked))
            elapsed = (time.perf_counter() - t0) / len(part)
            for k, i in enumerate(part):
                if int(raw.status[k]) != OK:
                    one = jax.tree.map(lambda leaf, k=k: leaf[k], raw)
                    raise SimulationError(f"{labels[i] or scenarios[i].name}: "
                                          + _failure_message(scenarios[i], one, int(one.status)))
                if summary_only:
                    out[i] = _summary_of(scenarios[i], labels[i], raw, k, batch[k])
                else:
                    one = jax.tree.map(lambda leaf, k=k: leaf[k], raw)
                    out[i] = _result(scenarios[i], labels[i], batch[k], plans[i][1], one, elapsed)
            done += len(part)
            if progress is not None:
                progress(done, len(scenarios))
    return out


def _groups(scenarios, plans) -> list[list[int]]:
    """Runs that can share one compiled loop: same solver, effects and grid."""
    groups: dict = {}
    for i, (scenario, (plan, grid)) in enumerate(zip(scenarios, plans)):
        structure = jax.tree.structure(plan.effects)
        key = (scenario.simulation.solver, structure, np.asarray(plan.grid).tobytes())
        groups.setdefault(key, []).append(i)
    return list(groups.values())


def _pad_table(plan: Plan, length: int) -> Plan:
    """Repeat a force table's last row (and the duration as a boundary) up to ``length`` rows."""
    extra = length - int(plan.force_times.shape[0])
    if extra == 0:
        return plan
    times = np.concatenate([plan.force_times, np.repeat(plan.force_times[-1:], extra)])
    forces = np.concatenate([plan.force_values, np.repeat(plan.force_values[-1:], extra)])
    boundaries = np.concatenate([plan.boundaries, np.repeat(plan.duration[None], extra)])
    return dataclasses.replace(plan, force_times=times, force_values=forces, boundaries=boundaries)


def _chunk_for(rows: int, runs: int) -> int:
    per_run = rows * 8 * (2 * cm.STATE_SIZE + 24)  # states, outputs and masks of one run
    chunk = max(1, min(MAX_CHUNK, CHUNK_BYTES // per_run))
    chunk = 1 << int(math.log2(chunk))  # a power of two: few distinct compiled shapes
    return min(chunk, 1 << math.ceil(math.log2(runs)))


def _summary_of(scenario: Scenario, label: str, raw, k: int, plan: Plan) -> dict:
    """Run k of a batch, summarised from its end states and running extremes."""
    kinds = raw.event_kind[k, : int(raw.event_count[k])]
    return summarize(label, {name: values[k] for name, values in raw.extremes.items()}, plan.drivetrain,
                     plan.initial_state, raw.final_state[k], int(np.sum(kinds == cm.LOCK)),
                     int(np.sum(kinds == cm.UNLOCK)))


@functools.lru_cache(maxsize=None)
def compiled_batch(solver_name: str, max_segments: int, log_size: int):
    """The restart loop, vectorised over a leading batch axis of the plan."""
    solver = SOLVERS[solver_name]()
    return jax.jit(jax.vmap(functools.partial(_run, solver=solver, max_segments=max_segments, log_size=log_size)))

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
from pathlib import Path
from collections.abc import Callable
from dataclasses import dataclass, field

import jax
import numpy as np

from . import _jax
from .assemble import build_plan, loop_sizes
from .core.loop import OK, SOLVERS, Plan, _run
from .core.readout import Readout
from .periodic.analysis import periodic_regime
from .results import RunResult, summarize
from .scenario import Scenario, sweep_values
from .simulation import SimulationError, failure_message, run_result, simulate

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
    warnings: list[str] = field(default_factory=list)  # runs whose periodic regime did not settle, say

    def __len__(self) -> int:
        return len(self.labels)

    @property
    def summary(self) -> dict[str, np.ndarray]:
        """Column -> one value per run (labels included)."""
        return {key: np.asarray([row[key] for row in self.summaries]) for key in self.summaries[0]}

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
          resume: bool = False) -> SweepResult:
    """Run every value of the scenario's sweep (one run if it has none), vectorised.

    With ``output`` (a path), the results file is written as the chunks finish
    (:mod:`hoistsim.streaming`): memory stays at a chunk's worth, the result
    keeps the summaries only, and ``resume`` goes on from the chunks an
    interrupted run of the same sweep left in its partial file.
    """
    pairs = sweep_values(scenario)
    labels = [label for label, _ in pairs]
    scenarios = [one for _, one in pairs]
    keys = list(scenario.sweep or {})
    parameters = {key: np.asarray([swept_number(one, key) for one in scenarios]) for key in keys}
    started = time.perf_counter()
    warnings: list[str] = []
    stream = None
    if output is not None:
        from .streaming import StreamedFile

        stream = StreamedFile(output, scenario, labels, parameters, summary_only=summary_only, command=command,
                              resume=resume)
        if stream.discarded:
            warnings.append(f"{Path(output).name}: an interrupted sweep's {stream.discarded} chunk file(s) were "
                            "discarded (--resume keeps them)")
    try:
        outcome = simulate_many(scenarios, labels, summary_only=summary_only, chunk_size=chunk_size,
                                progress=progress, warnings=warnings, sink=stream,
                                skip_chunks=stream.chunks_done if stream is not None else 0)
        if stream is not None:
            for i, row in stream.written_summaries().items():
                if outcome[i] is None:
                    outcome[i] = row
            stream.finish()
    except SimulationError:
        if stream is not None:
            stream.discard()  # a run that fails would fail again: nothing to resume
        raise
    except BaseException:
        if stream is not None:
            stream.close()  # interrupted: the chunks stay for --resume
        raise
    streamed = summary_only or stream is not None
    return SweepResult(
        scenario=scenario,
        labels=labels,
        keys=keys,
        parameters=parameters,
        summaries=outcome if streamed else [run.summary for run in outcome],
        runs=None if streamed else outcome,
        stats={"wall_time": time.perf_counter() - started, "runs": len(labels)},
        warnings=warnings,
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
                  chunk_size: int | None = None, progress=None, warnings: list | None = None,
                  sink=None, skip_chunks: int = 0) -> list:
    """RunResults (or, with ``summary_only``, summary dicts) for many scenarios, in their order.

    A machine with a periodic regime keeps its event rows even for summaries:
    its regime is read from them.  ``warnings`` collects what the runs warn of.
    ``sink`` (:class:`hoistsim.streaming.StreamedFile`) takes each chunk as it
    finishes, and only the runs' summaries are kept; the first ``skip_chunks``
    chunks (a resumed sweep's, in the file already) are not run and stay None.
    """
    plans = [build_plan(s, summary_only=summary_only) for s in scenarios]
    if sink is not None:
        sink.begin([grid for _, grid in plans])
    out: list = [None] * len(scenarios)
    done, chunk_number = 0, 0
    for indices in _groups(scenarios, plans):
        group = [plans[i][0] for i in indices]
        group = _padded_tables(group)
        first = scenarios[indices[0]]
        max_switches = max(scenarios[i].simulation.max_switches for i in indices)
        sizes = tuple(max(n) for n in zip(*(loop_sizes(plan, max_switches) for plan in group)))
        periodic = any(e.cycles for e in group[0].elements)
        lean = summary_only and not periodic
        if lean:  # the summary needs no event rows, only their counts
            sizes = (sizes[0], 1)
        rows = int(group[0].grid.shape[0])
        chunk = chunk_size or _chunk_for(rows, group[0].layout.size, len(indices))
        layout = group[0].layout
        run, built = None, None
        for start in range(0, len(indices), chunk):
            part = indices[start:start + chunk]
            chunk_number += 1
            if chunk_number <= skip_chunks:  # in the file from before the interruption
                done += len(part)
                continue
            batch = group[start:start + chunk]
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
                logged = max(Readout(layout, raw, lane=k).event_count for k in range(len(part)))
                if lean or logged <= sizes[1]:
                    break
                sizes = loop_sizes(group[0], max_switches, log_size=logged + 1)  # room for every row
            for k, i in enumerate(part):
                one = Readout(layout, raw, lane=k)
                if one.status != OK:
                    if lean:  # the lean run kept no event rows: run it alone to say what happened
                        try:
                            simulate(scenarios[i])
                        except SimulationError as exc:
                            raise SimulationError(f"{labels[i] or scenarios[i].name}: {exc}") from None
                    raise SimulationError(f"{labels[i] or scenarios[i].name}: " + failure_message(scenarios[i], one))
                if summary_only:
                    values = one.summary()
                    regime = periodic_regime(scenarios[i], one) if periodic else None
                    if regime is not None:
                        values.update(regime.values())
                        if not regime.regime.settled and warnings is not None:
                            warnings.append(f"{labels[i] or scenarios[i].name}: {regime.regime.message}")
                    out[i] = summarize(labels[i], values, one.ledger(), one.count("lock"), one.count("unlock"))
                else:
                    out[i] = run_result(scenarios[i], labels[i], plans[i][1], one, elapsed)
                    if warnings is not None:
                        warnings.extend(out[i].warnings)
            if sink is not None:
                sink.write(part, [out[i] for i in part])
                if not summary_only:  # written: keep the summary, let the series go
                    for i in part:
                        out[i] = out[i].summary
            done += len(part)
            if progress is not None:
                progress(done, len(scenarios))
    return out


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


def _chunk_for(rows: int, states: int, runs: int) -> int:
    per_run = rows * 8 * (2 * states + 24)  # states, outputs and masks of one run
    chunk = max(1, min(MAX_CHUNK, CHUNK_BYTES // per_run))
    chunk = 1 << int(math.log2(chunk))  # a power of two: few distinct compiled shapes
    return min(chunk, 1 << math.ceil(math.log2(runs)))


@functools.lru_cache(maxsize=None)
def compiled_batch(solver_name: str, max_segments: int, log_size: int, columns: bool = True):
    """The restart loop, vectorised over a leading batch axis of the plan (without columns: summaries only)."""
    solver = SOLVERS[solver_name]()
    return jax.jit(jax.vmap(functools.partial(_run, solver=solver, max_segments=max_segments, log_size=log_size,
                                              columns=columns)))

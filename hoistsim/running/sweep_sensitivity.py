"""Sensitivities on every run of a sweep: each run's summaries and their derivatives, as summary columns.

Each run is differentiated as one run is (:mod:`hoistsim.running.sensitivity`):
its keys' directions in its own plan, then the run and its tangents through
the compiled loop.  Runs that share a structure go through one compiled call a
chunk at a time (the single run's program vmapped over the chunk's runs, split
over the devices as a sweep's are), so a sweep of any length compiles once.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import jax
import numpy as np

from .. import _jax
from .._pytree import static_values
from ..errors import ScenarioError
from ..machine.assemble import build_plan
from ..machine.elements import elements_for
from ..machine.core.readout import BatchReadout
from ..results.run_summaries import summary_columns
from ..results.summaries import Summaries
from ..scenario.loading import Scenario
from ..scenario.sweep_runs import SweepRuns
from ..scenario.sweep_spec import with_swept_value
from .blocks import LazyScenarios, check_status, devices_for, in_order, over_devices
from .block_plans import applies, block_plans, reached_positions, swept_changes
from ..results.sensitivity_result import Sensitivity, differentiable_summaries, existing, units_over
from .derivative_program import along_directions
from .key_directions import PLAN_STEP, extrapolated, is_table, key_value, offsets, plan_direction, value_to_set
from .simulation import read_layout, scene_summary_units

# Runs a compiled call differentiates at once (a power of two up to this: few compiled shapes).  Each run's
# tangents make it (1 + keys) runs' work, and a chunk steps until its slowest run is done.
SWEEP_CHUNK = 256


@dataclasses.dataclass
class SweepSensitivity:
    """Each run's summaries and their derivatives with respect to each key (SI), in sweep order."""

    scenario: Scenario  # as given, sweep included
    labels: list[str]
    keys: list[str]  # the swept keys
    parameters: dict[str, np.ndarray]  # swept key -> each run's SI value (NaN for tables)
    wrt: dict[str, np.ndarray]  # key differentiated with respect to -> its value in each run (SI)
    key_units: dict[str, str]
    values: dict[str, np.ndarray]  # summary -> each run's value
    units: dict[str, str]  # summary -> its units
    derivatives: dict[str, dict[str, np.ndarray]]  # summary -> key -> each run's derivative; NaN: none exists
    summaries: Summaries  # every run's summary as a summary-only sweep keeps it, with d_<summary>_d_<key>
    tables: tuple[str, ...] = ()  # keys that hold a force table: their number is its largest force

    def __len__(self) -> int:
        return len(self.labels)

    def __getitem__(self, i: int) -> Sensitivity:
        """Run ``i``'s sensitivity, as :func:`hoistsim.sensitivity` gives one run's."""
        return Sensitivity(self.labels[i], {key: float(v[i]) for key, v in self.wrt.items()}, self.key_units,
                           {name: float(v[i]) for name, v in self.values.items()}, self.units,
                           {name: {key: float(d[i]) for key, d in by_key.items()}
                            for name, by_key in self.derivatives.items()}, self.tables)

    def elasticity(self, summary: str, key: str) -> np.ndarray:
        """Each run's (key / summary) * d summary / d key."""
        value = self.values[summary]
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(value != 0, self.wrt[key] / value * self.derivatives[summary][key], np.nan)

    def derivative_units(self, summary: str, key: str) -> str:
        return units_over(self.units[summary], self.key_units[key])

    def to_dict(self) -> dict:
        """``{"runs": [{"label": ..., "summary": {summary: {key: {"derivative", "elasticity", "unit"}}}}]}``:
        each run's as one run's ``to_dict``."""
        return {"runs": [{"label": self.labels[i], "summary": self[i].to_dict()} for i in range(len(self))]}

    @property
    def summary_units(self) -> dict[str, str]:
        """Units of every summary column of the file: the scene's summaries' and their derivatives'."""
        units = scene_summary_units(self.scenario)
        return units | {column_name(name, key): self.derivative_units(name, key)
                        for name in self.derivatives for key in self.wrt}

    def to_hdf5(self, path, command: str = "") -> None:
        """The sweep's summary-only results file, the derivatives as summary columns ``d_<summary>_d_<key>``."""
        from ..results.output import write_sweep
        from .sweeps import SweepResult

        result = SweepResult(self.scenario, self.labels, self.keys, self.parameters, self.summaries)
        write_sweep(path, result, command=command, units=self.summary_units)


def column_name(summary: str, key: str) -> str:
    return f"d_{summary}_d_{key}"


def sweep_sensitivity(scenario: Scenario, wrt: list[str], of: list[str] | None = None) -> SweepSensitivity:
    """:func:`hoistsim.sensitivity` on every run of ``scenario``'s sweep: each run differentiated at its own
    values, runs of one structure through one compiled call a chunk at a time."""
    if not wrt:
        raise ScenarioError("--wrt", "name at least one key, like --wrt clutch.kinetic_friction")
    runs = SweepRuns(scenario)
    count = len(runs)
    first = runs.scenario(0)
    plan, _ = build_plan(first, summary_only=True)
    layout = read_layout(plan, first)
    of = differentiable_summaries(layout.summaries, of)
    values = {key: np.full(count, key_value(first, key)) for key in wrt}
    unswept = _unreached_keys(runs, first, wrt)
    scenarios = LazyScenarios(runs)  # each run's, to say what went wrong in a run that failed
    chunks = _from_template(runs, first, plan, wrt, values, unswept)
    if chunks is None:
        chunks = _built_run_by_run(runs, scenarios, wrt, values, unswept)
    tangents = np.empty((count, len(wrt), 1 + layout.summary_count))  # as a run's scalars, up to its summaries
    columns: list = []
    for part, raw, d_scalars in chunks:
        check_status(runs, scenarios, part, 0, raw.layout, raw.first, lean=True)
        tangents[part] = np.asarray(d_scalars[: len(part), :, : tangents.shape[2]])
        batch = BatchReadout(raw.layout, raw.first, len(part))
        columns.append((np.asarray(part), summary_columns(runs.labels_of(np.asarray(part)), batch.summary(),
                                                          batch.ledger(), batch.count("lock"), batch.count("unlock"))))
    summaries = in_order(columns, count)
    value = {name: summaries.columns[name] for name in of}
    derivative = {name: {key: existing(value[name], tangents[:, k, 1 + layout.summary_slot(name)])
                         for k, key in enumerate(wrt)} for name in of}
    for name in of:
        for key in wrt:
            summaries.columns[column_name(name, key)] = derivative[name][key]
    units = scene_summary_units(first)
    from ..scenario.keys import key_units

    return SweepSensitivity(
        scenario, runs.labels, runs.keys, runs.parameters, values, {key: key_units(key) or "1" for key in wrt},
        value, {name: units.get(name, "") or "1" for name in of}, derivative, summaries,
        tuple(key for key in wrt if is_table(first, key)))


def _unreached_keys(runs: SweepRuns, first: Scenario, wrt: list[str]) -> set[str]:
    """The keys of ``wrt`` that reach no element a swept key reaches (:func:`reached_positions`: the scenario
    lowered with another value of the key): the elements they move are the same in every run, and so is each's
    direction (where the sweep's plans are built from a template at all: no swept ``simulation.`` or
    ``initial.`` key)."""
    if not applies(runs):
        return set()
    elements = elements_for(first)
    swept = reached_positions(elements, swept_changes(runs, list(range(len(runs))), first))
    return {key for key in wrt if not key.startswith(("simulation.", "initial.")) and key not in runs.keys
            and not reached_positions(elements, [_nudged(first, key)]) & swept}


def _nudged(scenario: Scenario, key: str) -> Scenario:
    """``scenario`` with ``key`` a step away from its value (a force table: scaled)."""
    x = key_value(scenario, key)
    return with_swept_value(scenario, key, value_to_set(scenario, key, x + PLAN_STEP * (abs(x) or 1.0)))


def _from_template(runs: SweepRuns, first: Scenario, plan, wrt: list[str], values: dict, unswept: set[str]):
    """Where no key is swept: the runs' plans from the first run's (:func:`block_plans`, as a summary-only sweep
    builds them), and so the plans either side of each key's value, all runs at once.  A key of ``unswept``
    has the first run's direction in every run.  None where the sweep's plans are not built so (or its runs'
    speed scales, a largest speed, differ)."""
    if any(key in runs.keys or key.startswith(("simulation.", "initial.")) for key in wrt):
        return None
    indices = list(range(len(runs)))
    fast = block_plans(runs, indices, summary_only=True)
    if fast is None or fast.per_run:
        return None
    template = fast.plan(0)
    same, moved = {}, {}  # key -> its direction in every run; key -> (the plans at its offsets, its step)
    for key in wrt:
        x = float(values[key][0])
        if key in unswept:
            same[key] = plan_direction(first, key, x, plan)
            if not _alike(same[key], template):
                return None
            continue
        h = PLAN_STEP * (abs(x) or 1.0)
        blocks = [block_plans(SweepRuns(with_swept_value(runs.base, key, value_to_set(runs.base, key, x + offset))),
                              indices, summary_only=True) for offset in offsets(h)]
        if any(b is None or b.per_run or not _alike(b.plan(0), template, statics=True) for b in blocks):
            return None
        moved[key] = blocks, h
    width = _width(len(runs))

    def directions(lanes: list[int], plans) -> object:
        base = jax.tree.leaves(plans)
        by_key = [_repeated(same[key], len(lanes)) if key in same else jax.tree.unflatten(
                      jax.tree.structure(plans),
                      extrapolated(base, [jax.tree.leaves(b.stacked(lanes)) for b in moved[key][0]], moved[key][1]))
                  for key in wrt]
        return jax.tree.map(lambda *leaves: _stack(leaves, axis=1), *by_key)  # (runs, keys, ...)

    def chunks():
        for offset in range(0, len(runs), width):
            part = list(range(offset, min(offset + width, len(runs))))
            lanes = part + [part[-1]] * (width - len(part))
            plans = fast.stacked(lanes)
            yield part, plans, directions(lanes, plans), first.simulation.solver, read_layout(template, first)

    return _results(chunks(), width)


def _alike(a, b, statics: bool = False) -> bool:
    """Two plans (or a plan and a direction) of one structure and shape (``statics``: the same static values)."""
    return (jax.tree.structure(a) == jax.tree.structure(b) and (not statics or static_values(a) == static_values(b))
            and [np.shape(x) for x in jax.tree.leaves(a)] == [np.shape(x) for x in jax.tree.leaves(b)])


def _built_run_by_run(runs: SweepRuns, scenarios: dict, wrt: list[str], values: dict, unswept: set[str]):
    """Every run's scenario, plan and directions built as one run's are; runs grouped by structure."""
    groups: dict = {}  # a compiled structure -> its runs' (index, scenario, plan)
    for i in range(len(runs)):
        run = scenarios[i]
        plan, _ = build_plan(run, summary_only=True)
        for key in wrt:
            values[key][i] = key_value(run, key)
        structure = (run.simulation.solver, jax.tree.structure(plan), static_values(plan),
                     tuple(np.shape(leaf) for leaf in jax.tree.leaves(plan)))
        groups.setdefault(structure, []).append((i, run, plan))
    for (solver, *_), group in groups.items():
        width = _width(len(group))
        directions = _directions(group, wrt, values, unswept)

        def chunks():
            for offset in range(0, len(group), width):
                lanes = group[offset:offset + width]
                part = [i for i, _, _ in lanes]
                lanes = lanes + [lanes[-1]] * (width - len(lanes))
                moved = directions[offset:offset + width]
                moved = moved + [moved[-1]] * (width - len(moved))
                yield part, _stacked([p for _, _, p in lanes]), _stacked(moved), solver, read_layout(lanes[0][2],
                                                                                                     lanes[0][1])

        yield from _results(chunks(), width)


def _directions(group: list, wrt: list[str], values: dict, unswept: set[str]) -> list:
    """Each run's keys' directions (stacked: one a key), for a group of runs ``(index, scenario, plan)`` of one
    structure.  A key of ``unswept`` moves the same elements the same way in every run: its direction is the
    group's first run's, where the speed scale (a largest speed, over the elements) cannot be the moved
    elements' in one run and not in another."""
    i, scenario, plan = group[0]
    scales = np.asarray([float(p.speed_scale) for _, _, p in group])
    same: dict = {}
    for key in unswept:
        direction = plan_direction(scenario, key, float(values[key][i]), plan)
        if np.all(scales == scales[0]) or (float(direction.speed_scale) == 0.0 and np.all(scales >= scales[0])):
            same[key] = direction
    return [jax.tree.map(lambda *leaves: np.stack(leaves),
                         *(same[key] if key in same else plan_direction(run, key, float(values[key][r]), p)
                           for key in wrt))
            for r, run, p in group]


def _width(runs: int) -> int:
    """Runs a compiled call takes: a power of two (few compiled shapes), at most SWEEP_CHUNK."""
    return min(SWEEP_CHUNK, 1 << math.ceil(math.log2(runs)))


@dataclasses.dataclass
class _Raw:
    layout: object
    first: object  # the chunk's runs' raw outputs, the first direction's (every direction's run is one)


def _results(chunks, width: int):
    """(the chunk's run indices, its raw outputs, its scalars' derivatives (runs, keys, scalars)) for each of
    ``chunks``: (run indices, stacked plans and directions padded to ``width``, solver, layout)."""
    devices = devices_for(width)
    for part, plans, directions, solver, layout in chunks:
        program = _jax.executable(functools.partial(_sweep_program, solver, devices), plans, directions,
                                  name=f"sweep-derivatives-{solver}", devices=devices)
        raw, d_scalars, _, _ = jax.device_get(program(plans, directions))
        yield part, _Raw(layout, jax.tree.map(lambda leaf: leaf[:, 0], raw)), d_scalars


def _repeated(tree, count: int):
    """``tree``'s leaves each repeated on a new leading axis of ``count``."""
    return _stacked([tree] * count)


def _stacked(trees: list):
    """Pytrees stacked on a leading axis."""
    return jax.tree.map(lambda *leaves: _stack(leaves), *trees)


def _stack(leaves, axis: int = 0):
    """np.stack, a tangent's float0 leaves (which hold nothing) as float0 zeros."""
    if np.asarray(leaves[0]).dtype == jax.dtypes.float0:
        shape = list(np.shape(leaves[0]))
        return np.zeros((*shape[:axis], len(leaves), *shape[axis:]), jax.dtypes.float0)
    return np.stack(leaves, axis=axis)


@functools.lru_cache(maxsize=None)
def _sweep_program(solver: str, devices: int):
    """The single run's derivative program (summaries only) vmapped over a chunk's runs, split over devices."""
    return over_devices(jax.vmap(along_directions(solver, 1, 0, False)), devices)

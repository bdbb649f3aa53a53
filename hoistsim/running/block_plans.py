"""A block's plans built from its first run's: only the elements a swept key reaches are built for each run.

A sweep's runs differ in their swept keys alone.  Building every run's
scenario and plan in full (pydantic copies, the swept values validated again,
every part written out and its element built) costs about as much as the runs
themselves.  Here the first run of a block is built in full, the template;
every other run has its swept values set on the template's scenario as they
were validated when the file was read (no checks run again: each value passed
them then), and only the parts a swept key reaches are written out again
(:func:`hoistsim.scenario.lowering.lowered_again`) and their elements built.
A part is reached by a key where the scenario lowered with another of the
key's values builds it otherwise (:func:`reached_positions`): whatever the
part reads of the scenario, a hoist's or a drawn drivetrain's.  Each block's
middle and last runs are also built the full way and compared leaf by leaf:
on any difference the block is built the full way, as it is wherever this does
not apply (a swept ``simulation.`` key, a key in a section the sweep adds).
A hoist started at its steady lift has its starting speeds worked out again
for each run's values, as its lowering does.  Full output is built so too: its
runs share the output grid as they share the simulation.
"""

from __future__ import annotations

import dataclasses
from types import SimpleNamespace

import jax
import numpy as np
from pydantic import BaseModel

from .._pytree import static_values
from ..machine.assemble import build_plan, plan_from
from ..machine.core.plan import Plan
from ..machine.core.schedule import scheduled_times
from ..machine.elements import REGISTRY, element_class, elements_for
from ..scenario.lowering import lower, lowered_again
from ..scenario.steady_lift import with_steady_lift
from ..scenario.sweep_spec import with_validated_value
from ..scenario.swept_values import SweptValues


def reached_positions(elements: tuple, changed: list) -> set[int]:
    """The positions of a scenario's ``elements`` that another value of its keys reaches: those built otherwise
    from any scenario of ``changed`` (the same scenario, a key or two set to other values)."""
    reached = set()
    for other in changed:
        others = elements_for(other)
        if len(others) != len(elements):  # another value adds or drops a part: every element is reached
            return set(range(len(elements)))
        reached |= {k for k, (a, b) in enumerate(zip(elements, others)) if not _same_element(a, b)}
    return reached


def swept_changes(runs, indices: list[int], scenario) -> list:
    """For each swept key that takes more than one value over runs ``indices``, ``scenario`` (the first's) with
    the key at another of them: the scenarios :func:`reached_positions` compares."""
    where = runs.positions_of(np.asarray(indices))
    changed = []
    for key, p in zip(runs.keys, where):
        other = np.flatnonzero(p != p[0])
        if other.size:
            changed.append(with_validated_value(scenario, key, runs.base.provenance.swept[key].validated[
                int(p[other[0]])]))
    return changed


def _same_element(a, b) -> bool:
    """Two elements built alike: one class, structure and static values, every leaf equal."""
    if type(a) is not type(b) or static_values(a) != static_values(b):
        return False
    if jax.tree.structure(a) != jax.tree.structure(b):
        return False
    return all(np.shape(x) == np.shape(y) and np.array_equal(x, y, equal_nan=True)
               for x, y in zip(jax.tree.leaves(a), jax.tree.leaves(b)))


def applies(runs) -> bool:
    """Whether a sweep's summary-only plans can be built from a template (see the module's text)."""
    base = getattr(runs, "base", None)
    if base is None or not runs.keys or any(key not in base.provenance.swept for key in runs.keys):
        return False
    if any(key.startswith("simulation.") for key in runs.keys):
        return False
    # a key in a section the sweep adds has no value validated alone: each run is validated whole
    return not any(isinstance(kept, list) and None in kept
                   for kept in (base.provenance.swept[key].validated for key in runs.keys))


class BlockPlans:
    """The plans of a block's runs: the template's, and for each rebuilt element a column of its runs.

    Kept apart rather than as a plan per run: a chunk is stacked from them at once
    (:meth:`stacked`), the shared elements broadcast.  A column is either one
    element built for every run at once (:class:`StackedElements`) or a list of
    elements built one by one (:class:`ListedElements`, padded to the block's
    longest tables: each row added is one more boundary at the end).
    """

    def __init__(self, template: Plan, rebuilt: dict[int, object], sim, runs: int, grid: np.ndarray):
        self.template, self.rebuilt, self.runs = template, rebuilt, runs
        self.grid = grid  # every run's output times (unpadded)
        duration = float(sim.duration)
        shared = [e for k, e in enumerate(template.elements) if k not in rebuilt]
        fixed = np.array([0.0, duration, *scheduled_times(shared)], dtype=float)
        own = [column.boundaries() for column in rebuilt.values()]
        self.boundaries = np.clip(np.concatenate([np.broadcast_to(fixed, (runs, fixed.size)), *own], axis=1),
                                  0.0, duration)
        # the starting state and speed scale: the template's, unless a rebuilt element starts otherwise
        self.per_run = any(column.starts_apart() for column in rebuilt.values())

    def plan(self, r: int) -> Plan:
        """Run ``r``'s plan (its tables padded as the block's)."""
        elements = tuple(self.rebuilt[k].element(r) if k in self.rebuilt else e
                         for k, e in enumerate(self.template.elements))
        return _with_start(dataclasses.replace(self.template, elements=elements, boundaries=self.boundaries[r]),
                           self.per_run)

    def stacked(self, lanes: list[int]) -> Plan:
        """The plans of runs ``lanes``, stacked on a leading axis (one compiled call's chunk)."""
        n = len(lanes)
        elements = tuple(self.rebuilt[k].stacked(lanes) if k in self.rebuilt else
                         jax.tree.map(lambda leaf: _repeated(leaf, n), element)
                         for k, element in enumerate(self.template.elements))
        if self.per_run:
            starts = [self.plan(r) for r in lanes]
            initial = np.stack([p.initial_state for p in starts])
            scale = np.stack([p.speed_scale for p in starts])
        else:
            initial, scale = _repeated(self.template.initial_state, n), _repeated(self.template.speed_scale, n)
        rest = {f.name: _repeated(getattr(self.template, f.name), n) for f in dataclasses.fields(self.template)
                if f.name not in ("elements", "boundaries", "initial_state", "speed_scale")}
        return dataclasses.replace(self.template, elements=elements, boundaries=self.boundaries[lanes],
                                   initial_state=initial, speed_scale=scale, **rest)


class ListedElements:
    """One position's elements, built run by run, their tables padded to the longest."""

    def __init__(self, elements: list):
        self.elements = padded(elements)

    def element(self, r: int):
        return self.elements[r]

    def stacked(self, lanes: list[int]):
        return jax.tree.map(lambda *leaves: np.stack(leaves), *[self.elements[r] for r in lanes])

    def boundaries(self) -> np.ndarray:
        times = [scheduled_times([e]) for e in self.elements]
        width = max(len(t) for t in times)
        return np.array([t + [np.inf] * (width - len(t)) for t in times], dtype=float).reshape(len(times), width)

    def starts_apart(self) -> bool:
        first = _start(self.elements[0])
        return first != ((), (), None) and any(_start(e) != first for e in self.elements)


class StackedElements:
    """One position's element for every run of a block, built once from the runs' swept values stacked:
    each leaf either the runs' (a leading axis of runs) or shared by all (the template's)."""

    def __init__(self, template, stacked, runs: int):
        self.template, self.runs = template, runs
        shared, self.treedef = jax.tree.flatten(template)
        self.shared = [np.asarray(leaf) for leaf in shared]
        self.leaves = []  # per leaf: the runs' values, or None where every run has the template's
        for own, leaf in zip(jax.tree.leaves(stacked), self.shared):
            own = np.asarray(own)
            if own.shape == (runs,) + leaf.shape and np.array_equal(own[0], leaf, equal_nan=True):
                self.leaves.append(own)
            elif own.shape == leaf.shape and np.array_equal(own, leaf, equal_nan=True):
                self.leaves.append(None)
            else:
                raise ValueError("a leaf is neither the runs' nor the template's")
        self.stacked_element = stacked

    def element(self, r: int):
        return jax.tree.unflatten(self.treedef, [leaf if own is None else own[r]
                                                 for own, leaf in zip(self.leaves, self.shared)])

    def stacked(self, lanes: list[int]):
        return jax.tree.unflatten(self.treedef, [_repeated(leaf, len(lanes)) if own is None else own[lanes]
                                                 for own, leaf in zip(self.leaves, self.shared)])

    def boundaries(self) -> np.ndarray:
        """Each run's scheduled times (its tables' knots, its own times), a row a run."""
        every = self.stacked(list(range(self.runs)))  # every leaf with the runs' axis
        columns = [np.asarray(getattr(every, times), float) for times, _ in every.tables().values()]
        columns += [np.asarray(t, float).reshape(self.runs, 1) for t in every.boundaries()]
        return np.concatenate(columns, axis=1) if columns else np.zeros((self.runs, 0))

    def starts_apart(self) -> bool:
        every = self.stacked(list(range(self.runs)))
        scale = every.speed_scale()
        for value in [*every.bodies().values(), *every.states().values(), *([] if scale is None else [scale])]:
            value = np.broadcast_to(np.asarray(value, float), (self.runs,))
            if not np.all(value == value[0]):
                return True
        return False


def _start(element) -> tuple:
    """What an element gives the starting state and the speed scale."""
    return (tuple(float(v) for v in element.bodies().values()), tuple(float(v) for v in element.states().values()),
            element.speed_scale())


def _repeated(leaf, n: int) -> np.ndarray:
    """A leaf shared by every run of a chunk, with the chunk's leading axis (a view, no copy)."""
    return np.broadcast_to(leaf, (n,) + np.shape(leaf))


def _with_start(plan: Plan, per_run: bool) -> Plan:
    """The plan with its starting state and speed scale worked out from its own elements (``per_run``)."""
    if not per_run:
        return plan
    sim = SimpleNamespace(duration=float(plan.duration), rtol=plan.rtol, atol=plan.atol,
                          max_switches=plan.max_switches)
    own = plan_from(plan.elements, sim, plan.grid)
    return dataclasses.replace(plan, initial_state=own.initial_state, speed_scale=own.speed_scale)


def padded(elements: list) -> list:
    """One position's elements with every table as long as the longest (its last row repeated)."""
    longest: dict = {}
    for e in elements:
        for name, (times, _) in e.tables().items():
            longest[name] = max(longest.get(name, 0), int(np.shape(getattr(e, times))[0]))
    out = []
    for e in elements:
        changes = {}
        for name, fields in e.tables().items():
            extra = longest[name] - int(np.shape(getattr(e, fields[0]))[0])
            for f in fields if extra else ():
                column = np.asarray(getattr(e, f))
                changes[f] = np.concatenate([column, np.full(extra, column[-1])])
        out.append(dataclasses.replace(e, **changes) if changes else e)
    return out


def block_plans(runs, indices: list[int], summary_only: bool = True) -> BlockPlans | None:
    """The plans of runs ``indices`` of a :class:`hoistsim.scenario.sweep_runs.SweepRuns`, from the first
    one's; None where that does not apply or a checked run differs (build them in full then).  Every run
    of a sweep that applies to has the first one's output grid (no ``simulation.`` key is swept)."""
    if not applies(runs):
        return None
    template_scenario = runs.scenario(indices[0])
    template, grid = build_plan(template_scenario, summary_only=summary_only)
    parts = lower(template_scenario, REGISTRY).parts
    # worked out for each block (the scenario lowered again for each key swept over it), not kept on the runs
    positions = sorted(reached_positions(template.elements, swept_changes(runs, indices, template_scenario)))
    for columns in (_stacked_columns, _listed_columns):
        rebuilt = columns(runs, indices, template, template_scenario, parts, positions)
        if rebuilt is None:
            continue
        plans = BlockPlans(template, rebuilt, template_scenario.simulation, len(indices), grid)
        if all(same_plan(build_plan(runs.scenario(indices[r]), summary_only=summary_only)[0], plans.plan(r))
               for r in {len(indices) // 2, len(indices) - 1} - {0}):
            return plans
    return None


def _stacked_columns(runs, indices, template, scenario, parts, positions) -> dict | None:
    """Each rebuilt element built once for the whole block, from its part written out from the scenario with
    every run's swept values stacked (a leading axis of runs); None where a swept value does not stack (tables
    of different lengths, words), or writing the part out or ``from_spec`` does not take arrays."""
    stacks = {}
    for key in runs.keys:  # kept as columns as the sweep was read (a list: values that do not stack)
        kept = runs.base.provenance.swept[key].validated
        stacks[key] = kept.stacked if isinstance(kept, SweptValues) else None
    if any(stacks[key] is None for key in runs.keys):
        return None
    for key, p in zip(runs.keys, runs.positions_of(np.asarray(indices))):
        scenario = with_validated_value(scenario, key, _taken(stacks[key], p))
    rebuilt = {}
    for k in positions:
        try:
            part = lowered_again(parts[k], with_steady_lift(scenario))
            element = element_class(part).from_spec(part.spec)
            if _statics(element) != _statics(template.elements[k]):
                return None
            rebuilt[k] = StackedElements(template.elements[k], element, len(indices))
        except Exception:  # noqa: BLE001  (arithmetic that is not elementwise: built run by run instead)
            return None
    return rebuilt


def _taken(stacked, rows):
    """The stacked values of ``rows`` (a model: each field's)."""
    if isinstance(stacked, BaseModel):
        return type(stacked).model_construct(**{name: _taken(getattr(stacked, name), rows)
                                               for name in type(stacked).model_fields})
    return stacked[rows]


def _listed_columns(runs, indices, template, template_scenario, parts, positions) -> dict | None:
    """Each rebuilt element built run by run, from its part written out from the scenario with the run's
    swept values (the template's scenario copied along each key's path only)."""
    built = {k: [template.elements[k]] for k in positions}
    statics = {k: _statics(template.elements[k]) for k in positions}
    validated = {key: runs.base.provenance.swept[key].validated for key in runs.keys}
    for i in indices[1:]:
        scenario = template_scenario
        for key, p in zip(runs.keys, runs.positions(i)):
            scenario = with_validated_value(scenario, key, validated[key][p])
        scenario = with_steady_lift(scenario)  # a hoist's starting speeds, where it starts at its steady lift
        for k, elements in built.items():
            part = lowered_again(parts[k], scenario)
            element = element_class(part).from_spec(part.spec)
            if _statics(element) != statics[k]:
                return None  # a swept key changes which element the part builds, or its structure
            elements.append(element)
    return {k: ListedElements(elements) for k, elements in built.items()}


def _statics(element) -> tuple:
    """An element's class and its structural fields: what one compiled program needs the same."""
    return type(element), static_values(element)


def same_plan(a: Plan, b: Plan) -> bool:
    """Two plans of one run the same: one structure, every leaf equal (the boundaries as sets, without the
    padding's: their order and repeats are free; the tables up to their own length)."""
    if jax.tree.structure(a) != jax.tree.structure(b):
        return False
    a = dataclasses.replace(_padded_as(a, b), boundaries=np.unique(a.boundaries))
    b = dataclasses.replace(b, boundaries=np.unique(b.boundaries))
    return all(np.shape(x) == np.shape(y) and np.array_equal(x, y, equal_nan=True)
               for x, y in zip(jax.tree.leaves(a), jax.tree.leaves(b)))


def _padded_as(plan: Plan, like: Plan) -> Plan:
    """``plan`` with its tables padded to the lengths of ``like``'s (as a block pads them)."""
    elements = tuple(padded([e, other])[0] for e, other in zip(plan.elements, like.elements))
    return dataclasses.replace(plan, elements=elements)

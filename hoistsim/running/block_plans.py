"""A block's plans built from its first run's: only the elements a swept key reaches are built for each run.

A sweep's runs differ in their swept keys alone.  Building every run's
scenario and plan in full (pydantic copies, the swept values validated again,
every element built) costs about as much as the runs themselves.  Here the
first run of a block is built in full, the template; every other run has its
swept values set on the template's sections as they were validated when the
file was read (no checks run again: each value passed them then), and only
the elements whose sections a swept key reaches are built again.  An element
is reached by a key of its own section or of a section its ``from_spec`` reads
from the scenario (seen once, by building it with the scenario behind a
recorder).  Each block's first, middle and last runs are also built the full
way and compared leaf by leaf: on any difference the block is built the full
way, as it is wherever this does not apply (a drawn drivetrain, a swept
``simulation.`` or ``initial.`` key, steady-lift starting speeds).  Full output
is built so too: its runs share the output grid as they share the simulation.
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
from ..machine.elements import element_sections
from ..scenario.sweep_spec import swept_field, with_validated_value
from ..scenario.swept_values import SweptValues


class _Recorder:
    """The scenario as an element's ``from_spec`` sees it, noting the sections read ("*": anything else)."""

    def __init__(self, scenario, read: set):
        object.__setattr__(self, "_scenario", scenario)
        object.__setattr__(self, "_read", read)

    def __getattr__(self, name):
        scenario = object.__getattribute__(self, "_scenario")
        object.__getattribute__(self, "_read").add(name if name in type(scenario).model_fields else "*")
        return getattr(scenario, name)


def reached_sections(scenario, keys) -> dict[str, set]:
    """The element sections a swept key reaches (the key is in the section, or in a section its ``from_spec``
    reads from the scenario), each with the swept sections it reads from the scenario ("*": it reads
    something else of it, so assume all)."""
    swept = {key.split(".")[0] for key in keys}
    reached = {}
    for section, spec, cls in element_sections(scenario):
        read: set = set()
        cls.from_spec(spec, _Recorder(scenario, read))
        through = swept if "*" in read else read & swept
        if through or section.split(".")[0] in swept:
            reached[section] = through
    return reached


def applies(runs) -> bool:
    """Whether a sweep's summary-only plans can be built from a template (see the module's text)."""
    base = getattr(runs, "base", None)
    if base is None or not runs.keys or any(key not in base.provenance.swept for key in runs.keys):
        return False
    if base.drivetrain is not None:  # several elements to a section: each run's built in full
        return False
    if any(key.startswith(("simulation.", "initial.")) for key in runs.keys) or base.initial.steady_lift:
        return False
    return True


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
    sections = element_sections(template_scenario)
    # worked out for each block (some 40 us: each element built once behind a recorder), not kept on the runs
    reach = reached_sections(template_scenario, runs.keys)
    positions = [k for k, (section, _, _) in enumerate(sections) if section in reach]
    for columns in (_stacked_columns, _listed_columns):
        rebuilt = columns(runs, indices, template, template_scenario, sections, reach, positions)
        if rebuilt is None:
            continue
        plans = BlockPlans(template, rebuilt, template_scenario.simulation, len(indices), grid)
        if all(same_plan(build_plan(runs.scenario(indices[r]), summary_only=summary_only)[0], plans.plan(r))
               for r in {len(indices) // 2, len(indices) - 1} - {0}):
            return plans
    return None


def _stacked_columns(runs, indices, template, scenario, sections, reach, positions) -> dict | None:
    """Each rebuilt element built once for the whole block, from its section with every run's swept values
    stacked (a leading axis of runs); None where an element reads a swept section from the scenario, a
    swept value does not stack (tables of different lengths, words), or ``from_spec`` does not take arrays."""
    if any(reach[sections[k][0]] for k in positions):
        return None
    stacks = {}
    for key in runs.keys:  # kept as columns as the sweep was read (a list: values that do not stack)
        kept = runs.base.provenance.swept[key].validated
        stacks[key] = kept.stacked if isinstance(kept, SweptValues) else None
    if any(stacks[key] is None for key in runs.keys):
        return None
    where = runs.positions_of(np.asarray(indices))
    values = [(key, _taken(stacks[key], p)) for key, p in zip(runs.keys, where)]
    rebuilt = {}
    for k in positions:
        section, spec, cls = sections[k]
        own = _section_with(spec, section, values)
        try:
            element = cls.from_spec(own, scenario)
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


def _listed_columns(runs, indices, template, template_scenario, sections, reach, positions) -> dict | None:
    """Each rebuilt element built run by run, from its section with the run's swept values."""
    built = {k: [template.elements[k]] for k in positions}
    statics = {k: _statics(template.elements[k]) for k in positions}
    # the scenario itself is copied with each run's values only where a rebuilt element reads a swept
    # section from it; else each rebuilt section alone is (the pydantic copies are most of a run's cost)
    whole = any(reach[sections[k][0]] for k in positions)
    validated = {key: runs.base.provenance.swept[key].validated for key in runs.keys}
    for i in indices[1:]:
        values = [(key, validated[key][p]) for key, p in zip(runs.keys, runs.positions(i))]
        scenario = template_scenario
        if whole:
            for key, value in values:
                scenario = with_validated_value(scenario, key, value)
        for k, elements in built.items():
            section, spec, cls = sections[k]
            own = swept_field(scenario, section) if whole else _section_with(spec, section, values)
            if type(own) is not type(spec) or getattr(own, "characteristic", None) != getattr(
                    spec, "characteristic", None):
                return None  # a swept key changes which element the section builds
            element = cls.from_spec(own, scenario)
            if _statics(element) != statics[k]:
                return None
            elements.append(element)
    return {k: ListedElements(elements) for k, elements in built.items()}


def _section_with(spec, section: str, values: list):
    """A section with the swept values under it set (validated already: copies, no checks)."""
    for key, value in values:
        if key.startswith(section + "."):
            spec = with_validated_value(spec, key[len(section) + 1:], value)
    return spec


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

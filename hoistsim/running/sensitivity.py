"""What moves the answer: each summary's derivative with respect to each scalar key, through every switch.

The run is differentiated forward (``jax.jvp``) through the compiled loop,
one direction a key and every key at once (``vmap`` over the directions):
every step of every pass, and at every switch the instant's derivative by the
implicit function theorem (:mod:`hoistsim.machine.core.event_time`), so a
lock-up time, a peak or a summary read after a switch moves as the run does.

A key's direction in the run's inputs (the plan: the elements' numbers) is
the plan's derivative with respect to the key, from plans built at values
either side of it (a central difference, extrapolated once: exact to
round-off where the plan is linear or quadratic in the key, as it is in a
mass, an inertia, a friction coefficient or a force).  A key whose change
would change the machine's structure (which elements, their tables' lengths)
has no derivative here and is refused.
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
from ..machine.core.loop import SOLVERS, restart_loop
from ..machine.core.plan import OK, STATUS_TEXT
from ..machine.core.readout import STATUS
from ..scenario.keys import check_key, key_units
from ..scenario.loading import Scenario
from ..scenario.sweep_spec import with_swept_value
from .simulation import SimulationError

# The relative step of the plan's central difference (extrapolated once: its error is of the order of the
# step to the fourth power times the plan's fifth derivative in the key, and round-off / step).
PLAN_STEP = 1e-3


@dataclasses.dataclass
class Sensitivity:
    """Each summary's value and its derivative with respect to each key (SI units), a scenario's."""

    name: str
    keys: dict[str, float]  # key -> its value (SI)
    key_units: dict[str, str]
    values: dict[str, float]  # summary -> its value
    units: dict[str, str]  # summary -> its units
    derivatives: dict[str, dict[str, float]]  # summary -> key -> d summary / d key (SI); NaN: none exists
    tables: tuple[str, ...] = ()  # keys that hold a force table: their number is its largest force

    def elasticity(self, summary: str, key: str) -> float:
        """(key / summary) * d summary / d key: the summary's relative change per relative change of the key."""
        value = self.values[summary]
        return self.keys[key] / value * self.derivatives[summary][key] if value else math.nan

    def derivative_units(self, summary: str, key: str) -> str:
        return _ratio(self.units[summary], self.key_units[key])

    def to_dict(self) -> dict:
        return {"name": self.name, "keys": {k: {"value": v, "units": self.key_units[k],
                                                **({"scales": "the table's forces"} if k in self.tables else {})}
                                            for k, v in self.keys.items()},
                "summaries": {s: {"value": self.values[s], "units": self.units[s],
                                  "derivatives": {k: {"value": d, "units": self.derivative_units(s, k),
                                                      "elasticity": self.elasticity(s, k)}
                                                  for k, d in self.derivatives[s].items()}}
                              for s in self.values}}


def sensitivity(scenario: Scenario, wrt: list[str], of: list[str] | None = None) -> Sensitivity:
    """The derivatives of ``of`` (summary names; None: every summary that is a number) with respect to each
    key of ``wrt`` (dotted scenario keys, each holding a number), at the scenario's values."""
    if scenario.sweep:
        raise ScenarioError("sweep", "a sensitivity is of one run: remove the sweep (or use --set for its key)")
    if not wrt:
        raise ScenarioError("--wrt", "name at least one key, like --wrt clutch.kinetic_friction")
    plan, _ = build_plan(scenario, summary_only=True)
    summaries = plan.layout.summaries
    numbers = [name for name, units in summaries.items() if units != "bool"]
    of = list(numbers if of is None else of)
    for name in of:
        if name not in summaries:
            raise ScenarioError("--of", f"no summary {name!r} in this scene; it has {', '.join(numbers)}")
        if summaries[name] == "bool":
            raise ScenarioError("--of", f"{name} is a yes/no: it has no derivative")
    values = {key: key_value(scenario, key) for key in wrt}
    directions = [plan_direction(scenario, key, values[key], plan) for key in wrt]
    stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *directions)
    solver = scenario.simulation.solver
    program = _jax.executable(functools.partial(_program, solver), plan, stacked, name=f"sensitivity-{solver}")
    scalars, tangents, counters = program(plan, stacked)
    scalars, tangents, counters = np.asarray(scalars[0]), np.asarray(tangents), np.asarray(counters[0])
    if int(counters[STATUS]):
        raise SimulationError(f"{scenario.name}: the run stopped at t = {float(scalars[0]):.6g} s: "
                              f"{STATUS_TEXT[int(counters[STATUS])]}")
    names = list(summaries)
    value = {name: float(scalars[1 + names.index(name)]) for name in of}
    derivative = {name: {key: _existing(value[name], float(tangents[k, 1 + names.index(name)]))
                         for k, key in enumerate(wrt)} for name in of}
    from ..results.output import summary_units

    units = summary_units(plan.layout)
    tables = tuple(key for key in wrt if hasattr(_held(scenario, key), "forces"))
    return Sensitivity(scenario.name, values, {key: key_units(key) or "1" for key in wrt}, value,
                       {name: units.get(name, "") or "1" for name in of}, derivative, tables)


def _existing(value: float, derivative: float) -> float:
    """The derivative, or NaN where the summary itself is none (a lock-up that never comes) or the
    derivative is not finite (a switch that only grazes its threshold)."""
    return derivative if math.isfinite(value) and math.isfinite(derivative) else math.nan


def key_value(scenario: Scenario, key: str, option: str = "--wrt") -> float:
    """The SI number a key holds; for a force table, its largest force (the table scaled with it)."""
    check_key(key, option, scenario.provenance.raw)
    held = _held(scenario, key, option)
    if hasattr(held, "forces"):
        return float(max(held.forces, key=abs))
    if type(held) is int:  # a count (teeth, surfaces): it moves in whole steps
        raise ScenarioError(f"{option} {key}", f"is a count ({held}), a whole number: it has no derivative")
    if isinstance(held, bool) or not isinstance(held, (int, float)):
        raise ScenarioError(f"{option} {key}", f"holds {held!r}, not a number: a derivative is taken with "
                                               "respect to a number")
    return float(held)


def value_to_set(scenario: Scenario, key: str, x: float):
    """The value to give ``key`` for its number to be ``x``: a force table's rows with every force scaled by
    x over its largest (its shape kept; the times as they are)."""
    held = _held(scenario, key, "--wrt")
    if not hasattr(held, "forces"):
        return x
    peak = float(max(held.forces, key=abs))
    if peak == 0.0:
        raise ScenarioError(f"--wrt {key}", "is a table of no force: there is no force to scale")
    return [[t, f * (x / peak)] for t, f in zip(held.times, held.forces)]


def _held(scenario: Scenario, key: str, option: str = "--wrt"):
    node = scenario
    for part in key.split("."):
        if isinstance(node, dict):
            node = node.get(part)
        elif isinstance(node, (list, tuple)):
            node = node[int(part)] if part.isdigit() and int(part) < len(node) else None
        else:
            node = getattr(node, part, None)
        if node is None:
            raise ScenarioError(f"{option} {key}", "is not set in this scenario: a derivative is taken where a "
                                                   "value is given")
    return node


def plan_direction(scenario: Scenario, key: str, x: float, plan, option: str = "--wrt"):
    """The derivative of ``plan`` (the scenario's, on any output grid) with respect to ``key`` at ``x``: the
    direction of the run's inputs the key moves them in (integer leaves: none)."""
    h = PLAN_STEP * (abs(x) or 1.0)

    def leaves_at(offset: float):
        moved, _ = build_plan(with_swept_value(scenario, key, value_to_set(scenario, key, x + offset)),
                              summary_only=True)
        moved = dataclasses.replace(moved, grid=plan.grid)  # the key does not move the output times
        if (jax.tree.structure(moved) != jax.tree.structure(plan) or static_values(moved) != static_values(plan)
                or any(np.shape(a) != np.shape(b) for a, b in zip(jax.tree.leaves(moved), jax.tree.leaves(plan)))):
            raise ScenarioError(f"{option} {key}", "changes the machine's structure near its value (which "
                                                   "elements, a table's rows): it has no derivative here")
        return [np.asarray(leaf) for leaf in jax.tree.leaves(moved)]

    def quotient(up, down, step):  # a leaf the key leaves as it is (an infinite limit too) does not move
        with np.errstate(invalid="ignore"):  # inf - inf, where np.where does not take it
            return [np.where(a == b, 0.0, (a - b) / step) for a, b in zip(up, down)]

    wide = quotient(leaves_at(h), leaves_at(-h), 2 * h)
    half = quotient(leaves_at(h / 2), leaves_at(-h / 2), h)
    leaves = [np.zeros(np.shape(base), jax.dtypes.float0) if np.asarray(base).dtype.kind != "f"
              else (4 * n - w) / 3 for base, w, n in zip(jax.tree.leaves(plan), wide, half)]
    return jax.tree.unflatten(jax.tree.structure(plan), leaves)


def _program(solver_name: str):
    """The jitted run and its derivative along each direction: (summaries, their tangents, counters); one
    compiled program a structure and count of keys (:func:`hoistsim._jax.executable` holds and stores it)."""
    solver = SOLVERS[solver_name]()

    def scalars(plan):
        raw = restart_loop(plan, solver=solver, log_size=1, step_room=0, columns=False)
        return raw.scalars, raw.counters

    def along(plan, direction):
        values, tangent, counters = jax.jvp(scalars, (plan,), (direction,), has_aux=True)
        return values, tangent, counters

    return jax.jit(lambda plan, directions: jax.vmap(along, in_axes=(None, 0))(plan, directions))


def _ratio(top: str, bottom: str) -> str:
    if bottom in ("", "1"):
        return top or "1"
    bottom = f"({bottom})" if any(c in bottom for c in "*/") else bottom
    return f"{top or '1'}/{bottom}"



def series_sensitivity(scenario: Scenario, wrt: list[str]):
    """The run, as :func:`hoistsim.simulate` gives it, with each series' derivative with respect to each key of
    ``wrt`` added as a series of its own, ``d_<series>_d_<key>`` (its units the series' over the key's; flags and
    modes have none), on the same rows: the output grid and the state just after each event."""
    import time

    from ..machine.assemble import log_rows, step_room
    from ..machine.core.readout import Readout
    from .simulation import failure_message, row_order, run_result

    if scenario.sweep:
        raise ScenarioError("sweep", "a sensitivity is of one run: remove the sweep (or use --set for its key)")
    plan, grid = build_plan(scenario)
    values = {key: key_value(scenario, key) for key in wrt}
    directions = [plan_direction(scenario, key, values[key], plan) for key in wrt]
    stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *directions)
    solver = scenario.simulation.solver
    sizes = (log_rows(plan), step_room(plan))
    while True:
        program = _jax.executable(functools.partial(_series_program, solver, *sizes), plan, stacked,
                                  name=f"series-sensitivity-{solver}-{sizes}")
        started = time.perf_counter()
        raw, at_grid, at_events = jax.device_get(program(plan, stacked))
        readout = Readout(plan.layout, jax.tree.map(lambda leaf: leaf[0], raw))
        elapsed = time.perf_counter() - started
        if not readout.log_overflowed and not readout.steps_overflowed:
            break
        sizes = (log_rows(plan, log_size=readout.event_count + 1), step_room(plan, readout.kept_steps))
    if readout.status != OK:
        raise SimulationError(failure_message(scenario, readout))
    run = run_result(scenario, "", grid, readout, elapsed)
    order, keep = row_order(grid, readout.events()[0])
    rows, events = grid.size, readout.event_count
    key_units_ = {key: key_units(key) or "1" for key in wrt}
    for i, (name, (units, _)) in enumerate(plan.layout.columns().items()):
        if units == "1":  # a flag or a mode: whole steps, no derivative
            continue
        for k, key in enumerate(wrt):
            derivative = np.concatenate([at_grid[k, i, :rows], at_events[k, i, :events]])[order][keep]
            column = f"d_{name}_d_{key}"
            run.series[column] = derivative
            run.units[column] = _ratio(units, key_units_[key])
            run.descriptions[column] = f"derivative of {name} with respect to {key} (at {values[key]:.6g})"
    return run


def _series_program(solver_name: str, log_size: int, room: int):
    """The jitted full run and, along each direction, the derivatives of its output columns at the grid's rows
    and at the events' rows."""
    solver = SOLVERS[solver_name]()

    def run(plan):
        return restart_loop(plan, solver=solver, log_size=log_size, step_room=room, columns=True)

    def along(plan, direction):
        raw, tangent = jax.jvp(run, (plan,), (direction,))
        return raw, tangent.grid_columns, tangent.event_columns

    return jax.jit(lambda plan, directions: jax.vmap(along, in_axes=(None, 0))(plan, directions))

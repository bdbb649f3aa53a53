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
import time

import jax
import numpy as np

from .. import _jax
from .._pytree import static_values
from ..errors import ScenarioError
from ..machine.assemble import build_plan
from ..machine.core.loop import SOLVERS, restart_loop
from ..machine.core.plan import OK, STATUS_TEXT
from ..scenario.keys import check_key, key_units
from ..scenario.loading import Scenario
from ..scenario.sweep_spec import held_at, with_swept_value
from .simulation import SimulationError, failure_message, row_order, run_result

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
    run: object = None  # with ``series``: the RunResult with each series' derivatives (d_<series>_d_<key>)

    def elasticity(self, summary: str, key: str) -> float:
        """(key / summary) * d summary / d key: the summary's relative change per relative change of the key."""
        value = self.values[summary]
        return self.keys[key] / value * self.derivatives[summary][key] if value else math.nan

    def derivative_units(self, summary: str, key: str) -> str:
        return _ratio(self.units[summary], self.key_units[key])

    def to_dict(self) -> dict:
        """``{summary: {key: {"derivative": d, "elasticity": e, "unit": "..."}}}``, SI; None where none exists."""
        def number(x: float):
            return x if math.isfinite(x) else None

        return {s: {k: {"derivative": number(d), "elasticity": number(self.elasticity(s, k)),
                        "unit": self.derivative_units(s, k)}
                    for k, d in self.derivatives[s].items()}
                for s in self.values}


def sensitivity(scenario: Scenario, wrt: list[str], of: list[str] | None = None,
                series: bool = False) -> Sensitivity:
    """The derivatives of ``of`` (summary names; None: every summary that is a number) with respect to each
    key of ``wrt`` (dotted scenario keys, each holding a number), at the scenario's values.  ``series``: the
    run too, as :func:`hoistsim.simulate` gives it, with each series' derivative with respect to each key as
    a series of its own, ``d_<series>_d_<key>`` (``Sensitivity.run``; from the same differentiated run)."""
    if scenario.sweep:
        raise ScenarioError("sweep", "a sensitivity is of one run: remove the sweep (or use --set for its key)")
    if not wrt:
        raise ScenarioError("--wrt", "name at least one key, like --wrt clutch.kinetic_friction")
    plan, grid = build_plan(scenario, summary_only=not series)
    summaries = plan.layout.summaries
    numbers = [name for name, units in summaries.items() if units != "bool"]
    of = list(numbers if of is None else of)
    for name in of:
        if name not in summaries:
            raise ScenarioError("--of", f"no summary {name!r} in this scene; it has {', '.join(numbers)}")
        if summaries[name] == "bool":
            raise ScenarioError("--of", f"{name} is a yes/no: it has no derivative")
    values = {key: key_value(scenario, key) for key in wrt}
    directions = stacked_directions(scenario, wrt, values, plan)
    readout, d_scalars, at_grid, at_events, elapsed = differentiated(plan, directions, scenario.simulation.solver,
                                                                     columns=series)
    if readout.status != OK:
        raise SimulationError(failure_message(scenario, readout) if series else
                              f"{scenario.name}: the run stopped at t = {readout.end_time:.6g} s: "
                              f"{STATUS_TEXT[readout.status]}")
    scalars, tangents = np.asarray(readout.raw.scalars), np.asarray(d_scalars)
    names = list(summaries)
    value = {name: float(scalars[1 + names.index(name)]) for name in of}
    derivative = {name: {key: _existing(value[name], float(tangents[k, 1 + names.index(name)]))
                         for k, key in enumerate(wrt)} for name in of}
    from ..results.output import summary_units

    units = summary_units(plan.layout)
    tables = tuple(key for key in wrt if hasattr(_held(scenario, key), "forces"))
    result = Sensitivity(scenario.name, values, {key: key_units(key) or "1" for key in wrt}, value,
                         {name: units.get(name, "") or "1" for name in of}, derivative, tables)
    if series:
        result.run = _with_series(run_result(scenario, "", grid, readout, elapsed), plan, readout, grid, values,
                                  result.key_units, at_grid, at_events)
    return result


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
    held = held_at(scenario, key)
    if held is None:
        raise ScenarioError(f"{option} {key}", "is not set in this scenario: a derivative is taken where a "
                                               "value is given")
    return held


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


def stacked_directions(scenario: Scenario, keys: list[str], values: dict, plan, option: str = "--wrt"):
    """Each key's :func:`plan_direction`, stacked on a leading axis (one a key)."""
    directions = [plan_direction(scenario, key, values[key], plan, option) for key in keys]
    return jax.tree.map(lambda *leaves: np.stack(leaves), *directions)


def differentiated(plan, directions, solver_name: str, columns: bool):
    """The run of ``plan`` and its derivatives along each of ``directions`` (stacked: one a key), one compiled
    program a structure and count of keys (:func:`hoistsim._jax.executable` holds and stores it):
    (the run's Readout, the derivatives of its scalars (keys, scalars), of its grid columns (keys, columns,
    rows) and of its event columns (keys, columns, events), the seconds the run took).  ``columns`` False: the
    summaries alone (no rows, a log that only counts), as a summary-only sweep's run; else room for every
    event row and kept step, the run taken again with more where it needed it."""
    from ..machine.assemble import log_rows, step_room
    from ..machine.core.readout import Readout

    sizes = (log_rows(plan), step_room(plan)) if columns else (1, 0)
    while True:
        program = _jax.executable(functools.partial(_program, solver_name, *sizes, columns), plan, directions,
                                  name=f"derivatives-{solver_name}-{sizes}-{columns}")
        started = time.perf_counter()
        raw, d_scalars, d_grid, d_events = jax.device_get(program(plan, directions))
        elapsed = time.perf_counter() - started
        readout = Readout(plan.layout, jax.tree.map(lambda leaf: leaf[0], raw))  # every direction's run is one
        if not columns or (not readout.log_overflowed and not readout.steps_overflowed):
            return readout, d_scalars, d_grid, d_events, elapsed
        sizes = (log_rows(plan, log_size=readout.event_count + 1), step_room(plan, readout.kept_steps))


def _program(solver_name: str, log_size: int, room: int, columns: bool):
    """The jitted run and, along each direction, the derivatives of its scalars and output columns."""
    solver = SOLVERS[solver_name]()

    def run(plan):
        return restart_loop(plan, solver=solver, log_size=log_size, step_room=room, columns=columns)

    def along(plan, direction):
        raw, tangent = jax.jvp(run, (plan,), (direction,))
        return raw, tangent.scalars, tangent.grid_columns, tangent.event_columns

    return jax.jit(lambda plan, directions: jax.vmap(along, in_axes=(None, 0))(plan, directions))


def _ratio(top: str, bottom: str) -> str:
    if bottom in ("", "1"):
        return top or "1"
    bottom = f"({bottom})" if any(c in bottom for c in "*/") else bottom
    return f"{top or '1'}/{bottom}"


def _with_series(run, plan, readout, grid, values: dict, units_of_keys: dict, at_grid, at_events):
    """``run`` with each output column's derivative along each key added as a series of its own (its units the
    column's over the key's; flags and modes have none), on the run's rows: the grid's and each event's."""
    order, keep = row_order(grid, readout.events()[0])
    rows, events = grid.size, readout.event_count
    for i, (name, (units, _)) in enumerate(plan.layout.columns().items()):
        if units == "1":  # a flag or a mode: whole steps, no derivative
            continue
        for k, key in enumerate(values):
            column = f"d_{name}_d_{key}"
            run.series[column] = np.concatenate([at_grid[k, i, :rows], at_events[k, i, :events]])[order][keep]
            run.units[column] = _ratio(units, units_of_keys[key])
            run.descriptions[column] = f"derivative of {name} with respect to {key} (at {values[key]:.6g})"
    return run

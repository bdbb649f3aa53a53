"""What moves the answer: each summary's derivative with respect to each scalar key, through every switch.

The run and its tangents come from :mod:`hoistsim.running.derivative_program` (forward mode through the
compiled loop, each switch's instant by the implicit function theorem), each key's direction in the run's
inputs from :mod:`hoistsim.running.key_directions`; a scenario with a sweep is differentiated run by run
in :mod:`hoistsim.running.sweep_sensitivity`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..errors import ScenarioError
from ..machine.assemble import build_plan
from ..machine.core.plan import OK, STATUS_TEXT
from ..results.sensitivity_result import Sensitivity, differentiable_summaries, existing, units_over
from ..scenario.keys import key_units
from ..scenario.loading import Scenario
from .derivative_program import differentiated
from .key_directions import is_table, key_value, stacked_directions
from .simulation import SimulationError, failure_message, read_layout, row_order, run_result

if TYPE_CHECKING:
    from .sweep_sensitivity import SweepSensitivity

__all__ = ["Sensitivity", "sensitivity"]


def sensitivity(scenario: Scenario, wrt: list[str], of: list[str] | None = None,
                series: bool = False) -> Sensitivity | SweepSensitivity:
    """The derivatives of ``of`` (summary names; None: every summary that is a number) with respect to each
    key of ``wrt`` (dotted scenario keys, each holding a number), at the scenario's values.  ``series``: the
    run too, as :func:`hoistsim.simulate` gives it, with each series' derivative with respect to each key as
    a series of its own, ``d_<series>_d_<key>`` (``Sensitivity.run``; from the same differentiated run).
    A scenario with a sweep: every run's, each at its own values (a
    :class:`hoistsim.running.sweep_sensitivity.SweepSensitivity`; no ``series``)."""
    if scenario.sweep:
        if series:
            raise ScenarioError("--series", "the series' derivatives are of one run: remove the sweep (or use "
                                            "--set for its key)")
        from .sweep_sensitivity import sweep_sensitivity

        return sweep_sensitivity(scenario, wrt, of)
    if not wrt:
        raise ScenarioError("--wrt", "name at least one key, like --wrt clutch.kinetic_friction")
    plan, grid = build_plan(scenario, summary_only=not series)
    layout = read_layout(plan, scenario)
    summaries = layout.summaries
    of = differentiable_summaries(summaries, of)
    values = {key: key_value(scenario, key) for key in wrt}
    directions = stacked_directions(scenario, wrt, values, plan)
    readout, d_scalars, at_grid, at_events, elapsed = differentiated(plan, directions, scenario.simulation.solver,
                                                                     columns=series, layout=layout)
    if readout.status != OK:
        raise SimulationError(failure_message(scenario, readout) if series else
                              f"{scenario.name}: the run stopped at t = {readout.end_time:.6g} s: "
                              f"{STATUS_TEXT[readout.status]}")
    scalars, tangents = np.asarray(readout.raw.scalars), np.asarray(d_scalars)
    value = {name: float(scalars[1 + layout.summary_slot(name)]) for name in of}
    derivative = {name: {key: float(existing(value[name], tangents[k, 1 + layout.summary_slot(name)]))
                         for k, key in enumerate(wrt)} for name in of}
    from ..results.output import summary_units

    units = summary_units(layout)
    tables = tuple(key for key in wrt if is_table(scenario, key))
    result = Sensitivity(scenario.name, values, {key: key_units(key) or "1" for key in wrt}, value,
                         {name: units.get(name, "") or "1" for name in of}, derivative, tables)
    if series:
        result.run = _with_series(run_result(scenario, "", grid, readout, elapsed), layout, readout, grid, values,
                                  result.key_units, at_grid, at_events)
    return result


def _with_series(run, layout, readout, grid, values: dict, units_of_keys: dict, at_grid, at_events):
    """``run`` with each output column's derivative along each key added as a series of its own (its units the
    column's over the key's; flags and modes have none), on the run's rows: the grid's and each event's."""
    order, keep = row_order(grid, readout.events()[0])
    rows, events = grid.size, readout.event_count
    for i, (name, (units, _)) in zip(layout.column_slots, layout.columns().items()):
        if units == "1":  # a flag or a mode: whole steps, no derivative
            continue
        for k, key in enumerate(values):
            column = f"d_{name}_d_{key}"
            run.series[column] = np.concatenate([at_grid[k, i, :rows], at_events[k, i, :events]])[order][keep]
            run.units[column] = units_over(units, units_of_keys[key])
            run.descriptions[column] = f"derivative of {name} with respect to {key} (at {values[key]:.6g})"
    return run

"""From a validated scenario to a run: build the plan, call the compiled loop, read the answer."""

from __future__ import annotations

import functools
import time as _time

import jax
import numpy as np

from .. import _jax
from ..errors import ScenarioError
from ..machine.assemble import build_plan, log_rows, step_room
from ..machine.core.element import MODE_NAMES
from ..machine.core.plan import CHATTERING, OK, SOLVER_FAILED, STATUS_TEXT
from ..machine.core.readout import Readout
from ..results.chunk_records import instant_categories
from ..results.output import summary_units
from ..results.run_result import RunResult
from ..scenario.loading import Scenario
from ..scenario.lowering import output_names


class SimulationError(RuntimeError):
    """A run that could not be completed (chattering, solver failure)."""


# The event rows and steps a run of each structure (its solver, its plan's tree, shapes and dtypes) needed, where
# that was more than its first estimate: the next run of it (a `watch` redraw, a fit's iteration) starts with
# room for them, instead of overflowing again and being run twice each time.
_ROOM_NEEDED: dict[tuple[str, str], tuple[int, int]] = {}


def simulate(scenario: Scenario, label: str = "") -> RunResult:
    """Run one scenario (its sweep, if any, is ignored here: see :func:`hoistsim.sweep`)."""
    plan, grid = build_plan(scenario)
    sim = scenario.simulation
    structure = (sim.solver, _jax.structure_of(plan))
    rows, room = _ROOM_NEEDED.get(structure, (log_rows(plan), step_room(plan)))
    while True:
        run = _jax.executable(functools.partial(_loop, sim.solver, rows, room), plan,
                              name=f"run-{sim.solver}-{rows}-{room}")
        started = _time.perf_counter()
        raw = Readout(read_layout(plan, scenario), jax.device_get(run(plan)))
        elapsed = _time.perf_counter() - started
        if not raw.log_overflowed and not raw.steps_overflowed:
            break
        # room for every event row and every step
        rows, room = log_rows(plan, log_size=raw.event_count + 1), step_room(plan, raw.kept_steps)
        before = _ROOM_NEEDED.get(structure, (0, 0))
        _ROOM_NEEDED[structure] = (max(rows, before[0]), max(room, before[1]))
    scenario_errors(scenario, raw)
    if raw.status != OK:
        raise SimulationError(failure_message(scenario, raw))
    return run_result(scenario, label, grid, raw, elapsed)


def _loop(solver: str, rows: int, room: int):
    """The compiled loop, imported (with the solver library) only where no stored program serves."""
    from ..machine.core.loop import compiled_run

    return compiled_run(solver, rows, room)


def scenario_errors(scenario: Scenario, raw: Readout) -> None:
    """A one-line ScenarioError where a run crossed a limit that says its scenario is wrong (an element's
    ``errors``: a rope wound onto the drum entirely), at the first such crossing."""
    times, kinds, _, _ = raw.events()
    for element in raw.layout.elements:
        for kind, (key, message) in element.errors.items():
            crossed = times[kinds == raw.layout.name(kind)]
            if crossed.size:
                raise ScenarioError(key, message.format(time=float(crossed.min())), source=scenario.source)


def failure_message(scenario: Scenario, raw: Readout) -> str:
    name = scenario.name
    t = raw.end_time
    if raw.status == CHATTERING:
        _, kinds, elements, _ = raw.events()
        switching = np.isin(kinds, raw.layout.switch_kinds)
        switches = [f"{e} {k}" for k, e in zip(kinds[switching], elements[switching])]
        culprit = max(set(elements[switching]), key=list(elements[switching]).count, default="a coupling")
        return (f"{name}: the {culprit} chatters: more than {scenario.simulation.max_switches} mode switches "
                f"by t = {t:.6g} s (last: {', '.join(switches[-4:])}); raise simulation.max_switches "
                "if this is real")
    if raw.status == SOLVER_FAILED:
        return (f"{name}: the {scenario.simulation.solver} solver failed at t = {t:.6g} s "
                f"(step size or step count limit); try a looser rtol or another solver")
    return f"{name}: the run stopped at t = {t:.6g} s: {STATUS_TEXT[raw.status]}"


def scene_summary_units(scenario: Scenario) -> dict[str, str]:
    """Units of every summary column a run of the scenario has (a sweep's, from its base scenario)."""
    from ..machine.assemble import machine_elements
    from ..machine.core.layout import Layout

    return summary_units(Layout(machine_elements(scenario)).named(output_names(scenario)))


def read_layout(plan, scenario: Scenario):
    """The plan's layout, its outputs under the names the scenario's results are written under (a hoist's
    ``slip_speed`` for its clutch's ``clutch_slip``): how a run of it is read back."""
    return plan.layout.named(output_names(scenario))


def row_order(grid: np.ndarray, event_time: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(order, keep) of the grid's rows followed by the event rows: their time order, and where an event falls
    on a grid time (or several events at one time) the last row kept, which holds the state after the switch."""
    times = np.concatenate([grid, event_time])
    order = np.argsort(times, kind="stable")
    times = times[order]
    return order, np.append(times[1:] != times[:-1], True)


def run_result(scenario: Scenario, label: str, grid: np.ndarray, raw: Readout, elapsed: float) -> RunResult:
    layout = raw.layout
    series = raw.columns(grid.size)
    event_time, kinds, elements, margins = raw.events()
    order, keep = row_order(grid, event_time)
    times = np.concatenate([grid, event_time])[order]
    series = {name: values[order][keep] for name, values in series.items()}
    # observations and the ends of cycles are rows, not events
    switches = ~np.isin(kinds, layout.observation_kinds + [kind for _, _, kind in layout.cycles])
    modes = np.asarray(raw.raw.event_modes[: raw.event_count])
    mode_after = [MODE_NAMES[int(modes[i, layout.coupling_index(e)])] if e in layout.coupling_names else ""
                  for i, e in enumerate(elements)]
    columns = layout.columns()
    periodic = None
    if scenario.periodic_regime is not None:  # its analysis (and scipy's root finder) only where there is one
        from ..results.periodic.analysis import periodic_regime

        periodic = periodic_regime(scenario, raw)
    category = instant_categories(layout, kinds)
    return RunResult(
        scenario=scenario,
        label=label,
        time=times[keep],
        series=series,
        units={name: units for name, (units, _) in columns.items()},
        summary_units=summary_units(layout),
        descriptions={name: text for name, (_, text) in columns.items()},
        events={
            "time": event_time[switches],
            "kind": kinds[switches],
            "element": elements[switches],
            "torque_margin": margins[switches],
            "mode_after": np.asarray(mode_after, dtype=object)[switches],
        },
        values={**raw.summary(), **(periodic.values() if periodic is not None else {})},
        periodic=periodic,
        grid=np.asarray(grid),
        instants={"time": event_time, "kind": kinds, "element": elements, "torque_margin": margins,
                  "mode_after": np.asarray(mode_after, dtype=object), "category": category},
        ledger=raw.ledger(),
        stats={**raw.stats, "wall_time": elapsed},
    )

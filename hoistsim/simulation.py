"""From a validated scenario to a run: build the plan, call the compiled loop, read the answer."""

from __future__ import annotations

import time as _time

import jax
import numpy as np

from . import _jax
from . import clutch_modes as cm
from .effects import effects_for
from .hybrid import CHATTERING, OK, SOLVER_FAILED, STATUS_TEXT, Plan, compiled_run
from .model import MODE_NAMES, Machine, initial_speeds
from .results import RunResult
from .scenario import Scenario
from .series import units_of


class SimulationError(RuntimeError):
    """A run that could not be completed (chattering, solver failure)."""


def output_grid(duration: float, interval: float) -> np.ndarray:
    """Output times 0, dt, 2 dt, ... and the duration itself."""
    count = int(np.floor(duration / interval * (1 + 1e-12))) + 1
    grid = np.arange(count, dtype=float) * interval
    grid = grid[grid < duration * (1 - 1e-12)]
    return np.append(grid, duration)


def _padded(grid: np.ndarray) -> np.ndarray:
    # Round the row count up to a power of two so that nearby durations share a compiled loop.
    size = max(64, 1 << int(np.ceil(np.log2(grid.size))))
    return np.concatenate([grid, np.full(size - grid.size, grid[-1])])


def _as_arrays(tree):
    # numpy leaves: cheap to build and to stack by the thousand; jit takes them as they are
    return jax.tree.map(lambda x: np.asarray(x, dtype=np.float64), tree)


def build_plan(scenario: Scenario, summary_only: bool = False) -> tuple[Plan, np.ndarray]:
    """The traced inputs of a run, and its (unpadded) output grid.

    ``summary_only`` keeps a single output row (the end): the summary comes from
    the loop's running extremes, so a large sweep need not store time series.
    """
    sim = scenario.simulation
    drivetrain = Machine.from_scenario(scenario).reduced()
    effects = effects_for(scenario)
    table = scenario.clutch.engagement_force
    scheduled = [0.0, sim.duration, *table.times, *(b for e in effects for b in e.boundaries())]
    grid = np.array([sim.duration]) if summary_only else output_grid(sim.duration, sim.output_interval)
    initial = [*initial_speeds(scenario, drivetrain), 0.0, 0.0, 0.0]
    plan = Plan(
        drivetrain=_as_arrays(drivetrain),
        force_times=np.asarray(table.times, dtype=np.float64),
        force_values=np.asarray(table.forces, dtype=np.float64),
        effects=_as_arrays(effects),
        boundaries=np.clip(np.asarray(scheduled, dtype=np.float64), 0.0, sim.duration),
        initial_state=np.asarray(initial, dtype=np.float64),
        duration=np.asarray(sim.duration, dtype=np.float64),
        grid=grid if summary_only else _padded(grid),
        rtol=np.asarray(sim.rtol, dtype=np.float64),
        atol=np.asarray(sim.atol, dtype=np.float64),
        max_switches=np.asarray(sim.max_switches),
    )
    return plan, grid


def loop_sizes(plan: Plan, max_switches: int) -> tuple[int, int]:
    """Static sizes of the loop: passes allowed and event rows kept."""
    # each pass ends at a boundary, a switch or an observation (as many allowed as switches)
    boundaries = int(plan.boundaries.shape[0])
    return boundaries + 2 * max_switches + 2, 2 * max_switches + 2 * boundaries + 4


def simulate(scenario: Scenario, label: str = "") -> RunResult:
    """Run one scenario (its sweep, if any, is ignored here: see :func:`hoistsim.sweep`)."""
    plan, grid = build_plan(scenario)
    sim = scenario.simulation
    sizes = loop_sizes(plan, sim.max_switches)
    run = _jax.executable(compiled_run(sim.solver, *sizes), plan, name=f"run-{sim.solver}-{sizes}")
    started = _time.perf_counter()
    raw = jax.device_get(run(plan))
    elapsed = _time.perf_counter() - started
    status = int(raw.status)
    if status != OK:
        raise SimulationError(_failure_message(scenario, raw, status))
    return _result(scenario, label, plan, grid, raw, elapsed)


def _failure_message(scenario: Scenario, raw, status: int) -> str:
    name = scenario.name
    t = float(raw.end_time)
    if status == CHATTERING:
        kinds = [cm.EVENT_KINDS[int(k)] for k in raw.event_kind[: int(raw.event_count)]]
        kinds = [kind for kind in kinds if kind in cm.SWITCH_KINDS]
        tail = ", ".join(kinds[-4:])
        return (f"{name}: the clutch chatters: more than {scenario.simulation.max_switches} mode switches "
                f"by t = {t:.6g} s (last: {tail}); raise simulation.max_switches if this is real")
    if status == SOLVER_FAILED:
        return (f"{name}: the {scenario.simulation.solver} solver failed at t = {t:.6g} s "
                f"(step size or step count limit); try a looser rtol or another solver")
    return f"{name}: the run stopped at t = {t:.6g} s: {STATUS_TEXT[status]}"


def _result(scenario: Scenario, label: str, plan: Plan, grid: np.ndarray, raw, elapsed: float) -> RunResult:
    rows = grid.size
    events = int(raw.event_count)
    series = {}
    for name, values in raw.grid_outputs.items():
        series[name] = np.concatenate([np.asarray(values)[:rows], np.asarray(raw.event_outputs[name])[:events]])
    times = np.concatenate([grid, np.asarray(raw.event_time)[:events]])
    # Rows in time order; where an event falls on a grid time (or several events at one
    # time) keep the last row, which holds the state after the switch.
    order = np.argsort(times, kind="stable")
    times = times[order]
    keep = np.append(times[1:] != times[:-1], True)
    series = {name: values[order][keep] for name, values in series.items()}
    kinds = np.asarray([cm.EVENT_KINDS[int(k)] for k in raw.event_kind[:events]], dtype=object)
    switches = np.isin(kinds, cm.SWITCH_KINDS)  # observations are rows, not events
    event_table = {
        "time": np.asarray(raw.event_time[:events], dtype=float)[switches],
        "kind": kinds[switches],
        "torque_margin": np.asarray(raw.event_margin[:events], dtype=float)[switches],
        "mode_after": np.asarray([MODE_NAMES[int(m)] for m in raw.event_mode[:events]], dtype=object)[switches],
    }
    return RunResult(
        scenario=scenario,
        label=label,
        drivetrain=plan.drivetrain,
        time=times[keep],
        series=series,
        units=units_of(plan.effects),
        events=event_table,
        extremes={k: float(v) for k, v in raw.extremes.items()},
        stats={
            "steps": int(raw.steps),
            "rejected_steps": int(raw.rejected_steps),
            "segments": int(raw.segments),
            "switches": int(raw.switch_count),
            "wall_time": elapsed,
        },
    )

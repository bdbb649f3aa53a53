"""From a validated scenario to the traced plan of a run: elements, boundaries, initial state, grid."""

from __future__ import annotations

import math

import jax
import numpy as np

from ..errors import ScenarioError
from ..scenario.loading import Scenario
from .core.element import AbstractCoupling
from .core.layout import Layout, LayoutError
from .core.plan import Plan, expected_cycles
from .core.schedule import scheduled_times
from .elements import elements_for


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


_checked: set = set()  # element structures already found to fit together


def machine_elements(scenario: Scenario) -> tuple:
    """The scene's elements, checked to fit together (a bad fit is a one-line ScenarioError).

    The check depends on the structure alone (which elements, on which shafts),
    so a sweep pays it once.
    """
    elements = elements_for(scenario)
    structure = jax.tree.structure(elements)
    if structure not in _checked:
        try:
            Layout(elements)
        except LayoutError as exc:
            raise ScenarioError(exc.key, str(exc)) from None
        _checked.add(structure)
    return elements


def build_plan(scenario: Scenario, summary_only: bool = False) -> tuple[Plan, np.ndarray]:
    """The traced inputs of a run, and its (unpadded) output grid.

    ``summary_only`` keeps a single output row (the end): the summary comes from
    the loop's running extremes, so a large sweep need not store time series.
    """
    sim = scenario.simulation
    elements = machine_elements(scenario)
    grid = np.array([sim.duration]) if summary_only else output_grid(sim.duration, sim.output_interval)
    return plan_from(elements, sim, grid if summary_only else _padded(grid)), grid


def plan_from(elements: tuple, sim, grid: np.ndarray) -> Plan:
    """The plan of ``elements`` run as ``sim`` says, writing rows at ``grid`` (padded already)."""
    scheduled = [0.0, sim.duration, *scheduled_times(elements)]
    speeds = [float(v) for e in elements for v in e.bodies().values()]
    # the state in Layout's order: the bodies' speeds, every element's states, the angles read
    angles = dict.fromkeys(shaft for e in elements for shaft in e.angles())  # in Layout's order
    starts = {shaft: angle for e in elements for shaft, angle in e.angle_starts().items()}
    initial = (speeds + [float(v) for e in elements for v in e.states().values()]
               + [float(starts.get(shaft, 0.0)) for shaft in angles])
    scales = [float(s) for s in (e.speed_scale() for e in elements) if s is not None]
    return Plan(
        elements=elements,  # floats and float arrays already (from_spec); jit takes them as they are
        boundaries=np.clip(np.asarray(scheduled, dtype=np.float64), 0.0, sim.duration),
        initial_state=np.asarray(initial, dtype=np.float64),
        speed_scale=np.asarray(max(scales or [abs(v) for v in speeds] + [1.0]), dtype=np.float64),
        duration=np.asarray(sim.duration, dtype=np.float64),
        grid=grid,
        rtol=np.asarray(sim.rtol, dtype=np.float64),
        atol=np.asarray(sim.atol, dtype=np.float64),
        max_switches=np.asarray(sim.max_switches),
    )


def log_rows(plan: Plan, log_size: int | None = None) -> int:
    """The event log's rows, a static size of the loop: room for LOGGED_SWITCHES switches (each may log one row
    per coupling) and two rows a boundary; a machine with cycles (a period of its own) has rows for each
    expected cycle.  ``log_size`` asks for more (a run that logged more than it could keep is run again with
    room for them all).  The passes a run may take are the loop's own, traced (:func:`.core.plan.segment_budget`):
    neither depends on max_switches, so a new value of it compiles nothing."""
    couplings = max(1, sum(isinstance(e, AbstractCoupling) for e in plan.elements))
    rows = (couplings + 1) * LOGGED_SWITCHES + 2 * int(plan.boundaries.shape[0]) + 4
    rows += int(expected_cycles(plan)) * ROWS_PER_CYCLE
    if log_size is not None:
        rows = max(rows, _power_of_two(log_size))
    return rows


def step_room(plan: Plan, kept: int | None = None, sweep: bool = False) -> int:
    """The accepted steps a run keeps room for, for its output rows (a static size of the loop).  One run
    keeps room for a step a padded row (a hoist's start takes some 60-1 500 steps for 2 000-5 000 rows: a
    new value seldom outgrows it), and STEPS_PER_CYCLE_ONE_RUN for each cycle a machine with a period of its
    own is expected to turn (an engine's cycle is a hundred steps and more, between knots of its tables).  A
    sweep's chunk keeps room for a quarter of that with STEPS_PER_CYCLE a cycle, at least MIN_STEP_ROOM (room
    for a step a row in each of 256 runs is several times the memory of the rows themselves).  None where no
    row falls before the end (a summary's one row takes the final state).  ``kept`` asks for room for that
    many (a run that took more steps than it could keep is run again with room for them all)."""
    if not np.any(np.asarray(plan.grid) < float(plan.duration)):
        return 0
    cycles = int(expected_cycles(plan))
    if sweep:
        room = max(MIN_STEP_ROOM, max(int(plan.grid.shape[0]), cycles * STEPS_PER_CYCLE) // 4)
    else:
        room = max(int(plan.grid.shape[0]), cycles * STEPS_PER_CYCLE_ONE_RUN)
    return room if kept is None else max(room, _power_of_two(kept))


# Steps kept at first for each cycle a machine with a period of its own is expected to turn.
STEPS_PER_CYCLE = 128
# ... and in one run, twice that: one lane's room is cheap, a second compile is not (the engine hoist's knots,
# each stepped onto in two steps, take it some 160 steps a cycle: its first run outgrew 128 a cycle and was
# compiled and run again, 21 s of its first 25)
STEPS_PER_CYCLE_ONE_RUN = 256
MIN_STEP_ROOM = 256

# The switches the event log has room for at first (the default max_switches); a run that switches more is
# run again with room for every row.
LOGGED_SWITCHES = 200
# Rows a cycle is expected to log at first (its end, a few extremes, a few switches); more, and the run
# is repeated with room for what it logged.
ROWS_PER_CYCLE = 32


def _power_of_two(n: float) -> int:
    return 1 << max(0, math.ceil(math.log2(max(n, 1.0))))

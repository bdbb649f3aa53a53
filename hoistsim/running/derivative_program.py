"""The run and its derivatives along each key's direction, one compiled program a structure and count of keys.

The run is differentiated forward (``jax.jvp``) through the compiled loop,
one direction a key and every key at once (``vmap`` over the directions):
every step of every pass, and at every switch the instant's derivative by the
implicit function theorem (:mod:`hoistsim.machine.core.event_time`), so a
lock-up time, a peak or a summary read after a switch moves as the run does.
"""

from __future__ import annotations

import functools
import time

import jax

from .. import _jax
from ..machine.core.loop import SOLVERS, restart_loop


def differentiated(plan, directions, solver_name: str, columns: bool, layout=None):
    """The run of ``plan`` and its derivatives along each of ``directions`` (stacked: one a key), one compiled
    program a structure and count of keys (:func:`hoistsim._jax.executable` holds and stores it):
    (the run's Readout, the derivatives of its scalars (keys, scalars), of its grid columns (keys, columns,
    rows) and of its event columns (keys, columns, events), the seconds the run took).  ``columns`` False: the
    summaries alone (no rows, a log that only counts), as a summary-only sweep's run; else room for every
    event row and kept step, the run taken again with more where it needed it.  ``layout``: the plan's, as the
    run is read back (its outputs under its scenario's names: :func:`hoistsim.running.simulation.read_layout`)."""
    from ..machine.assemble import log_rows, step_room
    from ..machine.core.readout import Readout

    sizes = (log_rows(plan), step_room(plan)) if columns else (1, 0)
    while True:
        program = _jax.executable(functools.partial(_program, solver_name, *sizes, columns), plan, directions,
                                  name=f"derivatives-{solver_name}-{sizes}-{columns}")
        started = time.perf_counter()
        raw, d_scalars, d_grid, d_events = jax.device_get(program(plan, directions))
        elapsed = time.perf_counter() - started
        readout = Readout(layout or plan.layout, jax.tree.map(lambda leaf: leaf[0], raw))  # each direction's run is one
        if not columns or (not readout.log_overflowed and not readout.steps_overflowed):
            return readout, d_scalars, d_grid, d_events, elapsed
        sizes = (log_rows(plan, log_size=readout.event_count + 1), step_room(plan, readout.kept_steps))


def _program(solver_name: str, log_size: int, room: int, columns: bool):
    """The jitted run and, along each direction, the derivatives of its scalars and output columns."""
    return jax.jit(along_directions(solver_name, log_size, room, columns))


def along_directions(solver_name: str, log_size: int, room: int, columns: bool):
    """``(plan, directions) ->`` the run (one a direction, each the same) and, along each direction, the
    derivatives of its scalars and output columns: to be jitted (vmapped over runs first, for a sweep's)."""
    solver = SOLVERS[solver_name]()

    def run(plan):
        return restart_loop(plan, solver=solver, log_size=log_size, step_room=room, columns=columns)

    def along(plan, direction):
        raw, tangent = jax.jvp(run, (plan,), (direction,))
        return raw, tangent.scalars, tangent.grid_columns, tangent.event_columns

    return lambda plan, directions: jax.vmap(along, in_axes=(None, 0))(plan, directions)

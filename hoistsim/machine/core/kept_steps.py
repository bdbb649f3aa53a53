"""The accepted steps a run keeps for its output rows: a buffer written in place, one step at a time, and the
rows evaluated after the run, every row at once, on the steps that cover them.  A row costs its interpolant's
arithmetic alone, never a trip of a loop inside the step loop."""

from __future__ import annotations

import diffrax
import equinox as eqx
import jax
import jax.numpy as jnp

from .solver_step import Stepper, with_step_tolerances


class Steps(eqx.Module):
    """The accepted steps a run keeps for its output rows: each step's span, where its rows end (its end, or a
    crossing inside it), its dense output and the couplings' modes it was taken in.  A buffer of ``room``
    steps, the first ``count`` of them kept (the count may run past the room: the run is then taken again
    with room for them all)."""

    t0: jax.Array  # (room,) s
    t1: jax.Array  # (room,) s: the end of the step its interpolant spans
    until: jax.Array  # (room,) s: its rows are those before this (t1, or the crossing located in it)
    dense: dict  # the solver's dense output (its dense info: y0, y1, k...), each (room, ...)
    modes: jax.Array  # (room, couplings)


def no_steps(solver, y0, room: int, couplings: int) -> Steps:
    """A buffer for ``room`` steps of ``solver`` from states shaped as ``y0``."""
    # (an implicit solver steps with some tolerances: their values do not change the shapes)
    stepper = Stepper(with_step_tolerances(solver, diffrax.PIDController(rtol=1e-8, atol=1e-8)), None,
                       lambda t, y, args: y)
    dense = jax.eval_shape(lambda t0, t1, y: stepper.step(t0, t1, y, stepper.init(t0, t1, y))[2],
                           jnp.zeros((), y0.dtype), jnp.ones((), y0.dtype), y0)
    times = jnp.full((room,), jnp.inf)
    return Steps(t0=times, t1=times, until=times,
                 dense={name: jnp.zeros((room, *s.shape), s.dtype) for name, s in dense.items()},
                 modes=jnp.zeros((room, couplings), int))


def kept_step(steps: Steps, count, t0, t1, until, dense, modes, take):
    """The buffer with the step written at ``count`` (the first free place), and the count, one more if
    ``take``.  Written whether taken or not: a step not taken is written where the next one will be, and never
    read.  Where the buffer is full the write is dropped, never moved onto the last place: a step not taken
    would overwrite the last one kept (a run that filled its room exactly read its last step's rows as
    zeros), and a step taken past the room counts the run as one to take again.  (Writes alone, each
    ``.at[].set``: the buffer is written in place.)"""
    at = lambda leaf: leaf.at[count]
    written = Steps(t0=at(steps.t0).set(t0, mode="drop"), t1=at(steps.t1).set(t1, mode="drop"),
                    until=at(steps.until).set(until, mode="drop"),
                    dense={name: at(steps.dense[name]).set(value, mode="drop") for name, value in dense.items()},
                    modes=at(steps.modes).set(modes, mode="drop"))
    return written, count + take


def rows_from_steps(solver, kept: Steps, count, grid):
    """The state and the modes at each time of ``grid`` from the kept steps: each row on the interpolant of the
    step that covers it (the first whose rows end after it), every row at once.  A row no kept step covers
    (past where the steps end) is NaN, its modes -1."""
    room = kept.t0.shape[0]
    ends = jnp.where(jnp.arange(room) < count, kept.until, jnp.inf)
    found = jnp.searchsorted(ends, grid, side="right")
    covered = (found < jnp.minimum(count, room))[:, None]

    def row(i, t):
        dense = {name: leaf[i] for name, leaf in kept.dense.items()}
        return solver.interpolation_cls(t0=kept.t0[i], t1=kept.t1[i], **dense).evaluate(t), kept.modes[i]

    states, modes = jax.vmap(row)(jnp.minimum(found, room - 1), grid)
    return jnp.where(covered, states, jnp.nan), jnp.where(covered, modes, -1)

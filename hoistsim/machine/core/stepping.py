"""One pass of the integration, stepped in one loop: the solver's stages, its step-size controller, the guards.

A pass goes from where the last one stopped to the next scheduled boundary,
or to where a guard first falls to zero.  Each step is the solver's own
(its Butcher tableau, its dense interpolant) and diffrax's PID controller
decides the next; the guards are read at every accepted step's end, and a
crossing is located afterwards on that step's interpolant.  diffrax's
``diffeqsolve`` does the same, at about ten times the cost per step under
``vmap`` (its generic stage loop, saving and event machinery), which is what a
sweep pays for every step of every run.

The crossing found is the earliest of every guard that changed sign in the
step, not the first in list order: a bracket on "some guard that crossed in
this step is at or below zero", narrowed by the guards' own secant (regula
falsi with the Illinois rule, a few tries where halving takes forty) and stopped
on the bracket's width alone (guards are in rad/s or N*m, not seconds),
returning its upper end, the first time the crossing has happened, so that a
restart from there never meets it again.  Where several reach zero at that
instant, the first in list order fired (the switches, listed first).

The output rows are not written in the loop: each accepted step is kept (its
span and its dense output, a few numbers per state) and the rows are evaluated
after the run, every row at once, on the steps that cover them
(:func:`rows_from_steps`).  A row costs its interpolant's arithmetic alone,
never a trip of a loop inside the step loop.
"""

from __future__ import annotations

import functools
from collections.abc import Callable

import diffrax
import equinox as eqx
import jax
import jax.numpy as jnp

from . import private_api
from .crossing import crossing
from .dynamics import vector_field

# A bend of the rate ahead (its guard taken as a line over the last step): a step across it errs by the jump of
# the slope times how far past it the step goes, times the step, and is refused unless that is tiny.  So a step
# that would cross one stops short of it (by this fraction of the way to it: the line's own error over the way
# is smaller) ...
SHORT_OF_BEND = 1.0 - 1e-3
# ... and once the bend is this near (against the step just taken) the next step ends this little past it.
NEAR_BEND = 1e-2
PAST_BEND = 1.0 + 1e-6
# A step ending this many ulps short of the pass's end is taken to the end (as diffrax does).
END_ULPS = 100


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
    stepper = _Stepper(_with_step_tolerances(solver, diffrax.PIDController(rtol=1e-8, atol=1e-8)), None,
                       lambda t, y, args: y)
    dense = jax.eval_shape(lambda t0, t1, y: stepper.step(t0, t1, y, stepper.init(t0, t1, y))[2],
                           jnp.zeros((), y0.dtype), jnp.ones((), y0.dtype), y0)
    times = jnp.full((room,), jnp.inf)
    return Steps(t0=times, t1=times, until=times,
                 dense={name: jnp.zeros((room, *s.shape), s.dtype) for name, s in dense.items()},
                 modes=jnp.zeros((room, couplings), int))


def _kept(steps: Steps, count, t0, t1, until, dense, modes, take):
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


class Pass(eqx.Module):
    """Where a pass ended and why."""

    t: jax.Array  # s
    y: jax.Array
    hit: jax.Array  # a guard crossed zero at (t, y)
    mask: jax.Array  # (guards,): the guard that crossed there
    failed: jax.Array  # step limit reached, or the solver could not go on
    steps: jax.Array  # attempted, accepted and rejected
    rejected: jax.Array
    kept: Steps | None  # the accepted steps kept for the output rows (None: none are)
    count: jax.Array  # how many are kept, this pass's steps included
    proposed: jax.Array  # s: the step the controller would take next, had the pass gone on
    values: jax.Array  # (guards,): every guard where the pass ended


@functools.lru_cache(maxsize=None)
def _traced_once(field):
    """The vector field as a call of its own (a jitted function): a step reads it at each of its stages
    and a crossing's step again, and the program is traced and lowered with one copy of it instead of one
    a stage.  (XLA inlines the calls: the compiled program computes the same.)"""
    return jax.jit(field)


class _Stepper:
    """One step of an explicit Runge-Kutta solver, its stages written out from the tableau; any other
    diffrax solver (the implicit ones) through its own ``step``."""

    def __init__(self, solver, args, field):
        self.solver, self.args, self.vector_field = solver, args, _traced_once(field)
        self.term = diffrax.ODETerm(field)
        tableau = getattr(solver, "tableau", None)
        self.explicit = isinstance(solver, diffrax.AbstractERK) and tableau is not None
        if self.explicit:
            self.a = [[float(v) for v in row] for row in tableau.a_lower]
            self.c = [float(v) for v in tableau.c]
            self.b = [float(v) for v in tableau.b_sol]
            self.e = [float(v) for v in tableau.b_error]
            self.fsal, self.ssal = bool(tableau.fsal), bool(tableau.ssal)

    def field(self, t, y):
        return self.vector_field(t, y, self.args)

    def init(self, t0, t1, y0):
        """The state a step carries: the rate at its start (explicit), or the solver's own state."""
        if self.explicit:
            return self.field(t0, y0)
        return self.solver.init(self.term, t0, t1, y0, self.args)

    def step(self, t0, t1, y0, state):
        """(y1, error estimate, dense info, state after it, whether it could be taken)."""
        if not self.explicit:
            y1, error, dense, state, result = self.solver.step(self.term, t0, t1, y0, self.args, state, False)
            return y1, error, dense, state, result == diffrax.RESULTS.successful
        h = t1 - t0
        rates = [state if self.fsal else self.field(t0, y0)]

        def combined(weights):
            return sum((w * k for w, k in zip(weights, rates) if w != 0.0), jnp.zeros_like(y0))

        y1 = None
        for row, c in zip(self.a, self.c):
            last = len(rates) == len(self.a)
            if last and self.ssal:
                y1 = y0 + h * combined(row)
                stage = y1
            else:
                stage = y0 + h * combined(row)
            rates.append(self.field(t0 + c * h, stage))
        if y1 is None:
            y1 = y0 + h * combined(self.b)
        error = h * combined(self.e)
        dense = dict(y0=y0, y1=y1, k=h * jnp.stack(rates))
        return y1, error, dense, rates[-1] if self.fsal else state, jnp.ones((), bool)

    def interpolant(self, t0, t1, dense):
        return self.solver.interpolation_cls(t0=t0, t1=t1, **dense)


class _Carry(eqx.Module):
    t: jax.Array
    y: jax.Array
    t_next: jax.Array  # where the step being tried ends
    state: object
    control: object
    values: jax.Array  # the guards at (t, y)
    steps: jax.Array
    rejected: jax.Array
    done: jax.Array
    hit: jax.Array
    failed: jax.Array
    crossed: jax.Array  # (guards,): which changed sign in the last step
    reached: jax.Array  # (guards,): the guards at the last step's end (where they crossed, at a hit)
    proposed: jax.Array  # s: the controller's next step after the last accepted one
    cut: jax.Array  # whether the step being tried was cut short to reach a bend (its size is no step's measure)
    dense: dict | None  # the last step tried, its dense output, where a crossing's step is kept (else None)
    kept: Steps | None
    count: jax.Array


def integrate_pass(solver, args, guards: Callable, t0, y0, end, *, rtol, atol, dtmax, max_steps: int,
                   kept: Steps | None = None, count=0, modes=None, field: Callable = vector_field,
                   cap_until=jnp.inf, first_step=jnp.nan, bends=None, slopes0=None, values0=None,
                   crossing_step_kept: bool = True) -> Pass:
    """Step dy/dt = ``field(t, y, args)`` from (t0, y0) towards ``end`` until a guard (``guards(t, y, args)``:
    an array) falls to zero.  Steps start no longer than ``dtmax`` before ``cap_until`` (a pass solved again
    so that crossings found in one step get a step each: beyond the crossing that sent it back, a pass that
    has not crossed again steps as the error allows, rather than creep on capped).

    A guard crosses where it goes from positive at a step's start to zero or
    below at its end.  Each accepted step, and the crossing's step up to the
    crossing, is added to ``kept`` (from place ``count``, with ``modes``) for the
    output rows, when a buffer is given.

    ``first_step`` (s): the first step to try, where the last pass's steps carry over (its ``proposed``: the
    pass before ended at a table's knot, where nothing jumps); NaN: guessed from the rates at (t0, y0), as
    diffrax guesses it.

    ``bends`` (guards,): the guards where the rate bends (a table's knots): a step across one is refused for the
    bend's error, so a step that would cross one (as far as the guard's rate at the start, then its last step,
    foretells) stops just short of it, and the next ends just past it.  ``slopes0`` (guards,): their rates at
    (t0, y0) along the motion, where the caller knows them (else the guards' ``jvp``: every guard's, a second
    copy of the guards and their own tangents in the program).
    ``values0``: the guards at (t0, y0), where the caller has read them already.

    ``crossing_step_kept``: the last step tried is carried through the step loop (its dense output), so that a
    crossing's step is located on as it was taken; False: it is taken again once located.  One lane keeps it: a
    program with seven vector fields fewer to compile.  A vectorised sweep's lane takes it again: under vmap the
    carried step is written and selected lane by lane at every step, a quarter of a lane's cost, against a
    pass's stages taken again where it crosses.
    """
    controller = diffrax.PIDController(rtol=rtol, atol=atol)
    solver = _with_step_tolerances(solver, controller)
    stepper = _Stepper(solver, args, field)
    error_order = solver.error_order(stepper.term)
    floor = end - END_ULPS * (end - private_api.prevbefore(end))  # one ulp below the end, END_ULPS times over
    fresh = ~jnp.isfinite(first_step)

    def guessed():  # two rates and their norms: worked out only where some run has no step to carry over
        return controller.init(stepper.term, t0, end, y0, None, args, solver.func, error_order)[0]

    t0 = jnp.asarray(t0, y0.dtype)
    guess = jax.lax.cond(private_api.unvmap_any(fresh), guessed, lambda: t0)
    carried = jnp.where(fresh, 0.0, first_step)
    # (the controller's state at a start is the same either way: only its first step is carried over)
    _, control = controller.init(stepper.term, t0, end, y0, carried, args, solver.func, error_order)
    first = jnp.where(fresh, guess, t0 + carried)

    def capped(start, t1):  # the controller's dtmax, up to cap_until (t + min(dt, dtmax): the same float)
        return jnp.where(start < cap_until, jnp.minimum(t1, start + dtmax), t1)

    t_next = jnp.minimum(capped(t0, first), end)
    values = guards(t0, y0, args) if values0 is None else values0
    nothing = jnp.zeros_like(values, dtype=bool)
    state = stepper.init(t0, t_next, y0)
    first_cut = jnp.array(False)
    if bends is not None:  # the first step too stops short of a bend ahead: the guards' rates say where it is
        slopes = slopes0
        if slopes is None:
            rate = state if stepper.explicit and stepper.fsal else stepper.field(t0, y0)
            _, slopes = jax.jvp(lambda t, y: guards(t, y, args), (t0, y0), (jnp.ones_like(t0), rate))
        ahead = bends & (values > 0.0) & (slopes < 0.0)
        due = jnp.min(jnp.where(ahead, values / jnp.where(ahead, -slopes, 1.0), jnp.inf))
        foretold = t0 + due * jnp.where(due < NEAR_BEND * (t_next - t0), PAST_BEND, SHORT_OF_BEND)
        first_cut = (foretold > t0) & (foretold < t_next)
        t_next = jnp.where(first_cut, foretold, t_next)
    carry = _Carry(
        t=t0, y=y0, t_next=t_next, state=state, control=control, values=values,
        steps=jnp.array(0), rejected=jnp.array(0), done=t0 >= end, hit=jnp.array(False),
        failed=jnp.array(False), crossed=nothing, reached=values, proposed=first - t0, cut=first_cut,
        dense=_zeros_like(jax.eval_shape(stepper.step, t0, t_next, y0, state)[2]) if crossing_step_kept else None,
        kept=kept, count=jnp.asarray(count))

    def going(c: _Carry):
        return ~c.done & ~c.failed

    def body(c: _Carry) -> _Carry:
        y1, error, dense, state, taken = stepper.step(c.t, c.t_next, c.y, c.state)
        error = jnp.where(jnp.isnan(error) | ~taken, jnp.inf, error)
        keep, next_t0, next_t1, _, control, _ = controller.adapt_step_size(
            c.t, c.t_next, c.y, y1, args, error, error_order, c.control)
        # the step the error allows next; a step cut short (at the pass's end, or to reach a bend) proposes less
        # than the steps before it took, and does not lower what carries over
        proposal = next_t1 - next_t0
        shortened = (c.t_next >= end) | c.cut
        proposed = jnp.where(keep, jnp.where(shortened, jnp.maximum(c.proposed, proposal), proposal), c.proposed)
        cut = jnp.zeros((), bool)
        values = guards(c.t_next, y1, args)
        through = (c.values > 0.0) & (values <= 0.0)
        if bends is not None:
            # A bend of the rate (a table's knot) ahead: a step across it is refused for the bend's own error,
            # again and again as the controller shrinks it blindly towards the bend.  So the guard is taken as a
            # line, as it went over this step where the step was taken (over the part of it before the crossing
            # where the step was refused for crossing it), and the next step stops just short of where it reaches
            # zero; from there the bend is near, and the step after ends just past it: two steps a bend.
            h = c.t_next - c.t
            ahead = bends & (values > 0.0) & (values < c.values)
            due = jnp.min(jnp.where(ahead, values * h / jnp.where(ahead, c.values - values, 1.0), jnp.inf))
            crossed_bend = bends & through
            fraction = jnp.min(jnp.where(crossed_bend, c.values / jnp.where(crossed_bend, c.values - values, 1.0),
                                         jnp.inf))
            foretold = jnp.where(keep, c.t_next + due * jnp.where(due < NEAR_BEND * h, PAST_BEND, SHORT_OF_BEND),
                                 c.t + h * jnp.minimum(fraction * SHORT_OF_BEND, 1.0))
            cut = (foretold > next_t0) & (foretold < next_t1)
            next_t1 = jnp.where(cut, foretold, next_t1)
        next_t1 = capped(next_t0, next_t1)
        next_t1 = jnp.where(next_t1 > floor, jnp.where(keep, end, next_t0 + 0.5 * (end - next_t0)), next_t1)
        crossed = keep & through
        hit = jnp.any(crossed)
        kept, count = c.kept, c.count
        if kept is not None:  # an accepted step, for the rows it covers (an event's: once its crossing is found)
            kept, count = _kept(kept, count, c.t, c.t_next, c.t_next, dense, modes, keep & ~hit)
        accept = lambda new, old: jax.tree.map(lambda a, b: jnp.where(keep & ~hit, a, b), new, old)
        steps = c.steps + 1
        return _Carry(
            t=accept(c.t_next, c.t), y=accept(y1, c.y), t_next=jnp.where(keep & ~hit, next_t1, jnp.where(
                keep, c.t_next, next_t1)), state=accept(state, c.state), control=control,
            values=accept(values, c.values), steps=steps, rejected=c.rejected + ~keep,
            done=hit | (keep & (c.t_next >= end)), hit=hit, failed=(steps >= max_steps) & ~hit & ~(keep & (c.t_next >= end)),
            crossed=crossed, reached=values, proposed=proposed, cut=cut,
            dense=dense if crossing_step_kept else None, kept=kept, count=count)

    # The kept steps are a buffer: each written in place, never copied whole.  (Under ``vmap`` a loop's
    # carry is otherwise selected lane by lane at every step: the whole buffer, once a step.)
    c = private_api.while_loop(going, body, carry, kind="lax", buffers=lambda k: k.kept)

    # A crossing's step was not accepted: the carry still holds its start and end (and its dense output, where
    # kept), for its interpolant.
    def locate():
        dense = c.dense if crossing_step_kept else stepper.step(c.t, c.t_next, c.y, c.state)[2]
        interpolant = stepper.interpolant(c.t, c.t_next, dense)
        return dense, *crossing(guards, args, interpolant, c.t, c.t_next, c.crossed & c.hit, c.values,
                                  c.reached)

    def no_crossing():
        return _zeros_like(jax.eval_shape(stepper.step, c.t, c.t_next, c.y, c.state)[2]), c.t, c.y, nothing, c.values

    dense, t_hit, y_hit, mask, at_hit = jax.lax.cond(private_api.unvmap_any(c.hit), locate, no_crossing)
    t_end = jnp.where(c.hit, t_hit, c.t)
    y_end = jnp.where(c.hit, y_hit, c.y)
    kept, count = c.kept, c.count
    if kept is not None:  # the crossing's step, its rows up to the crossing
        kept, count = _kept(kept, count, c.t, c.t_next, t_end, dense, modes, c.hit)
    return Pass(t=t_end, y=y_end, hit=c.hit, mask=mask & c.hit, failed=c.failed, steps=c.steps, rejected=c.rejected,
                kept=kept, count=count, proposed=c.proposed, values=jnp.where(c.hit, at_hit, c.values))


def _zeros_like(shapes):
    """Zeros shaped as ``shapes`` (a tree of shapes and dtypes, as ``jax.eval_shape`` gives them)."""
    return jax.tree.map(lambda s: jnp.zeros(s.shape, s.dtype), shapes)


def _with_step_tolerances(solver, controller):
    """An implicit solver whose nonlinear solve takes the step controller's tolerances where it leaves them
    to it (diffrax's default; ``diffeqsolve`` does the same)."""
    if not isinstance(solver, diffrax.AbstractImplicitSolver):
        return solver
    names = [name for name in ("rtol", "atol", "norm")
             if getattr(solver.root_finder, name) is private_api.use_stepsize_tol]
    return eqx.tree_at(lambda s: tuple(getattr(s.root_finder, name) for name in names), solver,
                       tuple(getattr(controller, name) for name in names))


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

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

A table's knot (where a rate bends and nothing jumps) does not end a pass: a
step stops just short of it, the next ends just past it, and the guards that
watch it move on to the next knot (see ``passed_over``).  The output rows are
not written in the loop: each accepted step is kept (:mod:`.kept_steps`) and
the rows are evaluated after the run.
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
from .kept_steps import Steps, kept_step
from .solver_step import Stepper, with_step_tolerances
from .switching import KNOT_RESOLUTION

# A bend of the rate ahead (its guard taken as a line over the last step): a step across it errs by the jump of
# the slope times how far past it the step goes, times the step, and is refused unless that is tiny.  So a step
# that would cross one stops short of it (by this fraction of the way to it: the line's own error over the way
# is smaller) ...
SHORT_OF_BEND = 1.0 - 1e-3
# ... and once the bend is this near (against the step just taken) the next step ends this little past it.
NEAR_BEND = 1e-2
PAST_BEND = 1.0 + 1e-6
# A step taken past a knot that it does not end at: the knot reached this fraction of the step or more before its
# end (as the guard, taken as a line over the step, says) is a bend inside the step, and the step is taken again.
STRADDLE = 1e-5
# A step ending this many ulps short of the pass's end is taken to the end (as diffrax does).
END_ULPS = 100


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
    shift: jax.Array | None  # (guards,): added to the guards read, the knots passed over so far (None: none are)
    streak: jax.Array | None  # step attempts since the pass began or last passed over a knot (None: none are)


def integrate_pass(solver, args, guards: Callable, t0, y0, end, *, rtol, atol, dtmax, max_steps: int,
                   kept: Steps | None = None, count=0, modes=None, field: Callable = vector_field,
                   cap_until=jnp.inf, first_step=jnp.nan, bends=None, slopes0=None, values0=None,
                   crossing_step_kept: bool = True, passed_over=None, partners=None, longest=jnp.inf) -> Pass:
    """Step dy/dt = ``field(t, y, args)`` from (t0, y0) towards ``end`` until a guard (``guards(t, y, args)``:
    an array) falls to zero.  Steps start no longer than ``dtmax`` before ``cap_until`` (a pass solved again
    so that crossings found in one step get a step each: beyond the crossing that sent it back, a pass that
    has not crossed again steps as the error allows, rather than creep on capped), and never longer than
    ``longest`` (what the machine's torques in time allow: :meth:`.element.AbstractElement.longest_step`).

    A guard crosses where it goes from positive at a step's start to zero or
    below at its end.  Each accepted step, and the crossing's step up to the
    crossing, is added to ``kept`` (from place ``count``, with ``modes``) for the
    output rows, when a buffer is given.

    ``first_step`` (s): the first step to try, where the last pass's steps carry over (its ``proposed``: the
    pass before ended at a table's knot, where nothing jumps); NaN: guessed from the rates at (t0, y0), as
    diffrax guesses it.

    ``passed_over`` (guards,), a constant mask: knots that the pass steps over, not stops at (see
    :func:`.guard_roles.passed_over`).  Each is one of a pair of guards on a knot coordinate, the distance to
    the knot ahead and the distance from the knot behind, whole numbers apart; ``partners`` (guards,) gives each
    guard's pair.  An accepted step that takes the coordinate past a knot moves both on by the knots passed (a
    whole number added to each guard: nothing is read again), so that the pair watches the next knot either
    way; the step before it has stopped just short of the knot and this one ends just past it (``bends``), and a
    step that passes a knot more than ``STRADDLE`` of a step before its end is taken again short of it.
    ``max_steps`` counts the attempts since the pass began or last passed a knot.

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
    solver = with_step_tolerances(solver, controller)
    stepper = Stepper(solver, args, field)
    error_order = solver.error_order(stepper.term)
    floor = end - END_ULPS * (end - private_api.prevbefore(end))  # one ulp below the end, END_ULPS times over
    fresh = ~jnp.isfinite(first_step)
    read = guards  # the guards as the caller reads them; in the loop, moved on by the knots passed over

    def guards(t, y, args, shift):
        return read(t, y, args) if shift is None else read(t, y, args) + shift

    if passed_over is not None:
        passed_over, partners = jnp.asarray(passed_over), jnp.asarray(partners)

    def guessed():  # two rates and their norms: worked out only where some run has no step to carry over
        return controller.init(stepper.term, t0, end, y0, None, args, solver.func, error_order)[0]

    t0 = jnp.asarray(t0, y0.dtype)
    guess = jax.lax.cond(private_api.unvmap_any(fresh), guessed, lambda: t0)
    carried = jnp.where(fresh, 0.0, first_step)
    # (the controller's state at a start is the same either way: only its first step is carried over)
    _, control = controller.init(stepper.term, t0, end, y0, carried, args, solver.func, error_order)
    first = jnp.where(fresh, guess, t0 + carried)

    def capped(start, t1):  # the controller's dtmax, up to cap_until (t + min(dt, dtmax): the same float)
        return jnp.minimum(jnp.where(start < cap_until, jnp.minimum(t1, start + dtmax), t1), start + longest)

    t_next = jnp.minimum(capped(t0, first), end)
    values = read(t0, y0, args) if values0 is None else values0
    nothing = jnp.zeros_like(values, dtype=bool)
    state = stepper.init(t0, t_next, y0)
    first_cut = jnp.array(False)
    if bends is not None:  # the first step too stops short of a bend ahead: the guards' rates say where it is
        slopes = slopes0
        if slopes is None:
            rate = state if stepper.explicit and stepper.fsal else stepper.field(t0, y0)
            _, slopes = jax.jvp(lambda t, y: read(t, y, args), (t0, y0), (jnp.ones_like(t0), rate))
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
        kept=kept, count=jnp.asarray(count), shift=None if passed_over is None else jnp.zeros_like(values),
        streak=None if passed_over is None else jnp.array(0))

    def going(c: _Carry):
        return ~c.done & ~c.failed

    def body(c: _Carry) -> _Carry:
        y1, error, dense, state, taken = stepper.step(c.t, c.t_next, c.y, c.state)
        error = jnp.where(jnp.isnan(error) | ~taken, jnp.inf, error)
        keep, next_t0, next_t1, _, control, _ = controller.adapt_step_size(
            c.t, c.t_next, c.y, y1, args, error, error_order, c.control)
        values = guards(c.t_next, y1, args, c.shift)
        through = (c.values > 0.0) & (values <= 0.0)
        # where in the step each guard that crossed reached zero, the guard taken as a line over the step
        line_zero = c.values / jnp.where(through, c.values - values, 1.0)
        if passed_over is not None:
            # a knot passed over more than a hair before the step's end (where the guard, taken as a line over the
            # step, reached zero) is a bend inside the step: its error (the slope's jump, times the distance to
            # the step's nearer end, times the step) passes the embedded estimate in part, and each such step
            # adds it (taken, the engine's 14 000 knots left its series eight times as far from a run at rtol
            # 1e-12).  Taken again, ending just short of the knot, as a step refused.
            # (one within the knots' resolution of the step's start is reached where the step starts: it may be
            # nearer than the time's resolution allows a step to end short of it)
            past = (1.0 - line_zero) * (c.t_next - c.t)  # s: how long before the step's end it was reached
            straddled = keep & jnp.any(passed_over & through & (past > STRADDLE * c.proposed)
                                       & (c.values > KNOT_RESOLUTION))
            keep, next_t0 = keep & ~straddled, jnp.where(straddled, c.t, next_t0)
        # the step the error allows next; a step cut short (at the pass's end, or to reach a bend) proposes less
        # than the steps before it took, and does not lower what carries over
        proposal = next_t1 - next_t0
        shortened = (c.t_next >= end) | c.cut
        proposed = jnp.where(keep, jnp.where(shortened, jnp.maximum(c.proposed, proposal), proposal), c.proposed)
        # after a step cut short to reach a bend, the step the error allowed before it (not the controller's
        # growth from the short one: three or four steps more to each knot passed over)
        next_t1 = jnp.where(keep & c.cut, jnp.maximum(next_t1, next_t0 + proposed), next_t1)
        cut = jnp.zeros((), bool)
        crossed = keep & through & (True if passed_over is None else ~passed_over)
        hit = jnp.any(crossed)
        onward, shift, streak = values, c.shift, None if c.streak is None else c.streak + 1
        if passed_over is not None:
            # knots passed over by a step taken (not one that ends at a crossing, taken again up to it): each
            # pair moves on by the knots passed, the one side's count less the other's (whole numbers)
            passed = jnp.where(passed_over & through & keep & ~hit, jnp.floor(-values) + 1.0, 0.0)
            moved = passed - passed[partners]
            onward, shift = values + moved, shift + moved
            streak = jnp.where(jnp.any(passed > 0.0), 0, streak)
        if bends is not None:
            # A bend of the rate (a table's knot) ahead: a step across it is refused for the bend's own error,
            # again and again as the controller shrinks it blindly towards the bend.  So the guard is taken as a
            # line, as it went over this step where the step was taken (over the part of it before the crossing
            # where the step was refused for crossing it), and the next step stops just short of where it reaches
            # zero; from there the bend is near, and the step after ends just past it: two steps a bend.
            # (from the guards moved on past a knot just passed over, at the rate they fell over the step)
            h = c.t_next - c.t
            ahead = bends & (onward > 0.0) & (values < c.values)
            due = jnp.min(jnp.where(ahead, onward * h / jnp.where(ahead, c.values - values, 1.0), jnp.inf))
            crossed_bend = bends & through
            fraction = jnp.min(jnp.where(crossed_bend, line_zero, jnp.inf))
            foretold = jnp.where(keep, c.t_next + due * jnp.where(due < NEAR_BEND * h, PAST_BEND, SHORT_OF_BEND),
                                 c.t + h * jnp.minimum(fraction * SHORT_OF_BEND, 1.0))
            cut = (foretold > next_t0) & (foretold < next_t1)
            if passed_over is not None:
                cut = cut | (straddled & (foretold > next_t0))
            next_t1 = jnp.where(cut, foretold, next_t1)
        next_t1 = capped(next_t0, next_t1)
        next_t1 = jnp.where(next_t1 > floor, jnp.where(keep, end, next_t0 + 0.5 * (end - next_t0)), next_t1)
        kept, count = c.kept, c.count
        if kept is not None:  # an accepted step, for the rows it covers (an event's: once its crossing is found)
            kept, count = kept_step(kept, count, c.t, c.t_next, c.t_next, dense, modes, keep & ~hit)
        accept = lambda new, old: jax.tree.map(lambda a, b: jnp.where(keep & ~hit, a, b), new, old)
        steps = c.steps + 1
        return _Carry(
            t=accept(c.t_next, c.t), y=accept(y1, c.y), t_next=jnp.where(keep & ~hit, next_t1, jnp.where(
                keep, c.t_next, next_t1)), state=accept(state, c.state), control=control,
            values=accept(onward, c.values), steps=steps, rejected=c.rejected + ~keep,
            done=hit | (keep & (c.t_next >= end)), hit=hit,
            failed=((steps if streak is None else streak) >= max_steps) & ~hit & ~(keep & (c.t_next >= end)),
            crossed=crossed, reached=values, proposed=proposed, cut=cut,
            dense=dense if crossing_step_kept else None, kept=kept, count=count,
            shift=None if shift is None else accept(shift, c.shift), streak=streak)

    # The kept steps are a buffer: each written in place, never copied whole.  (Under ``vmap`` a loop's
    # carry is otherwise selected lane by lane at every step: the whole buffer, once a step.)
    c = private_api.while_loop(going, body, carry, kind="lax", buffers=lambda k: k.kept)

    # A crossing's step was not accepted: the carry still holds its start and end (and its dense output, where
    # kept), for its interpolant.
    def locate():
        dense = c.dense if crossing_step_kept else stepper.step(c.t, c.t_next, c.y, c.state)[2]
        interpolant = stepper.interpolant(c.t, c.t_next, dense)
        # (the guards moved on past the knots passed over, the shift an input: a located instant is differentiated
        # through the guards, which may close over no traced value)
        located, inputs = (read, args) if c.shift is None else (functools.partial(_shifted, read), (args, c.shift))
        return dense, *crossing(located, inputs, interpolant, c.t, c.t_next, c.crossed & c.hit, c.values, c.reached)

    def no_crossing():
        return _zeros_like(jax.eval_shape(stepper.step, c.t, c.t_next, c.y, c.state)[2]), c.t, c.y, nothing, c.values

    dense, t_hit, y_hit, mask, at_hit = jax.lax.cond(private_api.unvmap_any(c.hit), locate, no_crossing)
    t_end = jnp.where(c.hit, t_hit, c.t)
    y_end = jnp.where(c.hit, y_hit, c.y)
    kept, count = c.kept, c.count
    if kept is not None:  # the crossing's step, its rows up to the crossing
        kept, count = kept_step(kept, count, c.t, c.t_next, t_end, dense, modes, c.hit)
    return Pass(t=t_end, y=y_end, hit=c.hit, mask=mask & c.hit, failed=c.failed, steps=c.steps, rejected=c.rejected,
                kept=kept, count=count, proposed=c.proposed, values=jnp.where(c.hit, at_hit, c.values))


def _shifted(read, t, y, args_and_shift):
    """The guards ``read`` at (t, y), moved on past the knots passed over (``args_and_shift``: (args, shift))."""
    args, shift = args_and_shift
    return read(t, y, args) + shift


def _zeros_like(shapes):
    """Zeros shaped as ``shapes`` (a tree of shapes and dtypes, as ``jax.eval_shape`` gives them)."""
    return jax.tree.map(lambda s: jnp.zeros(s.shape, s.dtype), shapes)

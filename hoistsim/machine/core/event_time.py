"""The instant a guard crossed zero, with its derivative by the implicit function theorem.

The crossing is located by a bracketing search on the step's interpolant: its
value is exact to the bracket's width, but the search's comparisons carry no
derivative.  The instant t* is where the guard that fired is zero,

    g(t*, y(t*; p), p) = 0,

so, for any parameter p the run's inputs carry a tangent for,

    dt*/dp = -(dg/dp at fixed t) / (dg/dt along the interpolant),

where "at fixed t" takes in the interpolant's own dependence on p (its step's
start and end, its coefficients) and the guard's on the machine's values.
The state at the instant, evaluated on the interpolant at t*, then carries
dy/dt * dt*/dp besides its own derivative: the next pass starts from it, so a
switch's effect on everything after it (the flow's jump at the switch) follows
by the chain rule.  Only a derivative asks for this: the value is t* as
located, and a run that is not differentiated computes nothing more.

Where the guard only touches zero (a double root: a slip that just reaches
zero, a rope that just slackens) dg/dt is zero at t*: the instant is not a
differentiable function of p there (a little more or less and the switch
is lost or split in two), and the derivative is NaN, which every quantity
after it carries: "no derivative here".
"""

from __future__ import annotations

import functools

import jax
import jax.numpy as jnp


# A crossing whose guard falls this little over the step, at the rate it has at the root, against what it
# fell in all (from the step's start), only touches zero: it grazes, and no derivative exists.
GRAZING = 1e-6
# A located instant whose guard is still this far below zero (against its fall over the step) is no root: the
# guard jumped across zero where the step began.
JUMPED = 1e-6


@functools.partial(jax.custom_jvp, nondiff_argnums=(1,))
def event_time(t, guard, start, inputs):
    """``t``, the located zero of ``guard(t, inputs)`` (a scalar function of the instant and of traced
    ``inputs``: what it closes over must not be traced) after ``start`` (where the step began, the guard
    above zero), with its derivative as above: NaN where the guard only grazes zero."""
    del guard, start, inputs
    return t


@event_time.defjvp
def _event_time_jvp(guard, primals, tangents):
    t, start, inputs = primals
    _, d_start, d_inputs = tangents
    at_fixed_t = jax.jvp(lambda x: guard(t, x), (inputs,), (d_inputs,))[1]
    along = jax.jvp(lambda s: guard(s, inputs), (t,), (jnp.ones_like(t),))[1]
    at_start, at_root = guard(start, inputs), guard(t, inputs)
    fell = jnp.abs(at_start - at_root)
    # not a root: the guard stepped below zero as the step began (a table's knot, where a pass starts), so
    # the instant is the step's start, and moves as it does
    stepped = jnp.abs(at_root) > JUMPED * fell
    # transversal: the guard falls at a rate of the order of its fall over the step; a double root's
    # rate at the root is round-off
    grazing = ~stepped & ~(jnp.abs(along) * (t - start) > GRAZING * fell)
    crossing = -at_fixed_t / jnp.where(grazing | stepped, 1.0, along)
    return t, jnp.where(stepped, d_start, jnp.where(grazing, jnp.nan, crossing))

"""The instant a guard crossed zero, with its derivative by the implicit function theorem.

The crossing is located by bisection on the step's interpolant: its value is
exact to the bisection's tolerance, but a bisection's comparisons carry no
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
"""

from __future__ import annotations

import functools

import jax
import jax.numpy as jnp


@functools.partial(jax.custom_jvp, nondiff_argnums=(1,))
def event_time(t, guard, inputs):
    """``t``, the located zero of ``guard(t, inputs)`` (a scalar function of the instant and of traced
    ``inputs``: what it closes over must not be traced), with its derivative as above."""
    del guard, inputs
    return t


@event_time.defjvp
def _event_time_jvp(guard, primals, tangents):
    t, inputs = primals
    _, d_inputs = tangents
    at_fixed_t = jax.jvp(lambda x: guard(t, x), (inputs,), (d_inputs,))[1]
    along = jax.jvp(lambda s: guard(s, inputs), (t,), (jnp.ones_like(t),))[1]
    return t, -at_fixed_t / along

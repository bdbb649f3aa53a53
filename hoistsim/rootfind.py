"""Event location: bisection on the solver's dense output, to the last representable time.

diffrax hands the root finder a bracket [t_prev, t_next] over which a guard
went from positive to non-positive.  Newton's method on that interpolant can
stall at round-off, and optimistix's Bisection also asks the guard value to fall
below an absolute tolerance (guards are in rad/s or N*m, not seconds).  This
bisection stops on the width of the bracket alone and returns its upper end, the
first time at which the guard has crossed: the switch has happened there, so a
restart from that time never meets the same crossing again.
"""
# The guard list of a segment is short and fixed, so the Python ``sum`` over its
# leaves unrolls at trace time.

from __future__ import annotations

from collections.abc import Callable
from typing import Any, ClassVar

import equinox as eqx
import jax
import jax.numpy as jnp
import optimistix as optx
from jaxtyping import PyTree, Scalar


class _BracketState(eqx.Module):
    lower: Scalar  # guard > 0 here
    upper: Scalar  # guard <= 0 here
    done: jax.Array


class CrossingBisection(optx.AbstractRootFinder):
    """Bisection for a guard that is positive at ``lower`` and non-positive at ``upper``."""

    rtol: float = 1e-15
    atol: float = 1e-15
    norm: ClassVar[Callable[[PyTree], Scalar]] = jnp.abs

    def init(self, fn, y, args, options: dict[str, Any], f_struct, aux_struct, tags):
        del fn, y, args, aux_struct, tags
        dtype = jax.tree.leaves(f_struct)[0].dtype
        lower = jnp.asarray(options["lower"], dtype)
        upper = jnp.asarray(options["upper"], dtype)
        return _BracketState(lower=lower, upper=upper, done=jnp.array(False))

    def step(self, fn, y, args, options, state: _BracketState, tags):
        del options, tags
        middle = state.lower + 0.5 * (state.upper - state.lower)
        values, aux = fn(middle, args)
        # diffrax passes one value per guard, zero for all but the one that fired.
        crossed = sum(jax.tree.leaves(values)) <= 0
        lower = jnp.where(crossed, state.lower, middle)
        upper = jnp.where(crossed, middle, state.upper)
        # Stop when the bracket is within tolerance or no float lies strictly inside it.
        width_small = (upper - lower) <= self.atol + self.rtol * jnp.abs(upper)
        next_middle = lower + 0.5 * (upper - lower)
        exhausted = (next_middle <= lower) | (next_middle >= upper)
        return upper, _BracketState(lower=lower, upper=upper, done=width_small | exhausted), aux

    def terminate(self, fn, y, args, options, state: _BracketState, tags):
        del fn, y, args, options, tags
        return state.done, optx.RESULTS.successful

    def postprocess(self, fn, y, aux, args, options, state: _BracketState, tags, result):
        del fn, y, args, options, tags, result
        return state.upper, aux, {}

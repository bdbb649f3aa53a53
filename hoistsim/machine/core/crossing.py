"""Where in a step a guard first crossed zero: a bracket narrowed by the guards' own secant.

A pass ends at the earliest crossing of every guard that changed sign over its last step, located on that
step's interpolant (:mod:`.stepping`).  The bracket holds "some guard that crossed in this step is at or below
zero" at its upper end and not at its lower; each try reads every guard once at the earliest of the crossed
guards' secant roots, and moves one end.  Regula falsi alone keeps moving one end where a guard curves (its
root approached from one side for ever); the Illinois rule halves the guards' values at the end that stays, so
that the next try lands past the root and the bracket closes from both sides: a smooth guard's root to the
last representable time in some 5-10 reads of the guards, where halving a step to 1e-15 s takes 35-45.
"""

from __future__ import annotations

import functools

import jax
import jax.numpy as jnp

from . import private_api
from .event_time import event_time

# A crossing's bracket is narrowed until it is this narrow (absolute and relative to the time), or holds no float.
CROSSING_RTOL = 1e-15
CROSSING_ATOL = 1e-15
# After this many tries in a row that move the same end of the bracket, the next is a halving: the secant's
# worst case (a guard that bends sharply inside the bracket) is never slower than bisection by more than this.
SECANT_STALLS = 4


def crossing(guards, args, interpolant, lower, upper, crossed, at_lower, at_upper):
    """The earliest instant in (lower, upper] where a guard of ``crossed`` is at or below zero, the state
    there, which guard fired (the first in list order of those at or below zero there), and every guard there.

    ``at_lower``, ``at_upper``: every guard at the step's ends.  Each try reads the guards once, at the
    earliest of the secant roots of the guards at or below zero at the bracket's upper end (each guard taken
    as a line across the bracket), kept at least half the stopping width inside it (so that a root found
    ends the bracket at the next try); the try's answer (some crossed guard at or below zero there, or none)
    moves one end.  Where the same end moves twice in a row the guards' values at the other are halved (the
    Illinois rule: the secant then steps past the root and the bracket closes from both sides), and after
    ``SECANT_STALLS`` such tries the bracket is halved instead.
    """

    def width_left(hi):
        return CROSSING_ATOL + CROSSING_RTOL * jnp.abs(hi)

    def going(bracket):
        lo, hi = bracket[0], bracket[1]
        middle = lo + 0.5 * (hi - lo)
        return (hi - lo > width_left(hi)) & (middle > lo) & (middle < hi)

    def narrow(bracket):
        lo, hi, g_lo, g_hi, at_hi, fired, stalls = bracket
        width = hi - lo
        # each guard that has crossed by the upper end, as a line between the ends: where it reaches zero
        active = crossed & (g_hi <= 0.0)
        fraction = jnp.min(jnp.where(active, g_lo / jnp.where(active, g_lo - g_hi, 1.0), 1.0))
        margin = jnp.minimum(0.5 * width_left(hi), 0.25 * width)
        secant = jnp.clip(lo + fraction * width, lo + margin, hi - margin)
        middle = lo + 0.5 * width
        t = jnp.where((jnp.abs(stalls) >= SECANT_STALLS) | ~jnp.isfinite(secant), middle, secant)
        values = guards(t, interpolant.evaluate(t), args)
        at_t = crossed & (values <= 0.0)
        reached = jnp.any(at_t)
        # stalls: + tries in a row that moved the upper end, - the lower
        stalls = jnp.where(reached, jnp.maximum(stalls, 0) + 1, jnp.minimum(stalls, 0) - 1)
        g_lo = jnp.where(reached, jnp.where(stalls >= 2, 0.5 * g_lo, g_lo), values)
        g_hi = jnp.where(reached, values, jnp.where(stalls <= -2, 0.5 * g_hi, g_hi))
        stalls = jnp.where(t == middle, 0, stalls)  # a halving starts the count afresh
        return (jnp.where(reached, lo, t), jnp.where(reached, t, hi), g_lo, g_hi, jnp.where(reached, values, at_hi),
                jnp.where(reached, at_t, fired), stalls)

    # The guards at the bracket's upper end (as read: ``g_hi`` is halved by the Illinois rule) and those below
    # zero there are carried along, not worked out again where the search stops: the guards are most of the
    # program.
    _, t, _, _, at_t, fired, _ = jax.lax.while_loop(going, narrow, (lower, upper, at_lower, at_upper, at_upper,
                                                                    crossed, jnp.zeros((), int)))
    fired = jnp.where(jnp.any(fired), fired, crossed)  # round-off: the guard that crossed at the step's end
    which = jnp.arange(fired.shape[0]) == jnp.argmax(fired)
    # the instant's derivative, where the run is differentiated: the fired guard's zero (event_time)
    t = event_time(t, functools.partial(_fired_guard, guards), lower, (interpolant, args, which))
    y = interpolant.evaluate(t)
    # the guards there, read by the search where it moved the upper end (at the step's end, on the step's state:
    # read again on the interpolant's)
    at_t = jax.lax.cond(private_api.unvmap_any(t == upper), lambda: guards(t, y, args), lambda: at_t)
    return t, y, which, at_t


def _fired_guard(guards, t, inputs):
    """The guard that fired (``which``) at ``t`` on the step's interpolant."""
    interpolant, args, which = inputs
    return jnp.sum(jnp.where(which, guards(t, interpolant.evaluate(t), args), 0.0))

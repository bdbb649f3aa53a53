"""Tables of the state read inside the step loop: the knot interval holding a value, the table's value there,
and the knots counted along its argument (the kinks of a torque read from such a table).

The interval is found by comparing the value with every knot at once, not by a binary search: a search is a
``while`` loop (``jnp.searchsorted``'s default, and so ``jnp.interp``), and a loop nested in the step loop's
body costs XLA's CPU runtime a dispatch per operation of each trip, at every read of every stage.  The
tables here have tens to a few hundred knots, so the comparison is a few fused vector operations.  It gives
the same index as the search (the same comparison, the knots counted at or below the value), and
``interpolate`` the same arithmetic as ``jnp.interp``, so the answers are the same to the bit.
"""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

# Beyond a table's first and last knots the knot coordinate moves by one every this many of its argument's units
# (kelvin, rad/s): steadily, so that no crossing is missed, and slowly, so that the whole numbers it passes there
# (no knots) are 1e6 apart.
BEYOND_THE_TABLE = 1e6


def interval(value, knots):
    """The index k of the knot interval [knots[k], knots[k + 1]] that holds ``value``: the last that starts at
    or before it (at a repeated knot, the one after), the first below the table and the last above it."""
    at_or_below = jnp.searchsorted(knots, value, side="right", method="compare_all")
    return jnp.clip(at_or_below - 1, 0, knots.shape[0] - 2)


def interpolate(value, knots, values):
    """The table's value at ``value``: linear between its knots, held at the first and last values beyond them;
    ``jnp.interp(value, knots, values)`` to the bit (its formula: an interval no wider than a tiny fraction of
    a unit in the last place, a step, reads its left value)."""
    knots, values = jnp.asarray(knots), jnp.asarray(values)
    k = interval(value, knots)
    step = values[k + 1] - values[k]
    width = knots[k + 1] - knots[k]
    flat = jnp.abs(width) <= np.spacing(np.finfo(knots.dtype).eps)
    inside = jnp.where(flat, values[k], values[k] + ((value - knots[k]) / jnp.where(flat, 1, width)) * step)
    return jnp.where(value < knots[0], values[0], jnp.where(value > knots[-1], values[-1], inside))


def knots_passed(value, knots):
    """A table's knots counted along its argument (a temperature, a speed, a slip speed's size): a whole number
    exactly at each knot, rising steadily with the argument everywhere (beyond the ends by one every
    ``BEYOND_THE_TABLE``)."""
    inside = interpolate(value, knots, jnp.arange(knots.shape[0], dtype=knots.dtype))
    below = (value - knots[0]) / BEYOND_THE_TABLE
    above = knots.shape[0] - 1 + (value - knots[-1]) / BEYOND_THE_TABLE
    return jnp.where(value < knots[0], below, jnp.where(value > knots[-1], above, inside))

"""Where a table's knots are, counted along its argument: the kinks of a torque read from a table of the state."""

from __future__ import annotations

import jax.numpy as jnp

# Beyond a table's first and last knots the knot coordinate moves by one every this many of its argument's units
# (kelvin, rad/s): steadily, so that no crossing is missed, and slowly, so that the whole numbers it passes there
# (no knots) are 1e6 apart.
BEYOND_THE_TABLE = 1e6


def knots_passed(value, knots):
    """A table's knots counted along its argument (a temperature, a speed, a slip speed's size): a whole number
    exactly at each knot, rising steadily with the argument everywhere (beyond the ends by one every
    ``BEYOND_THE_TABLE``)."""
    inside = jnp.interp(value, knots, jnp.arange(knots.shape[0], dtype=knots.dtype))
    below = (value - knots[0]) / BEYOND_THE_TABLE
    above = knots.shape[0] - 1 + (value - knots[-1]) / BEYOND_THE_TABLE
    return jnp.where(value < knots[0], below, jnp.where(value > knots[-1], above, inside))

"""Where a table's knots are, counted along its argument: the kinks of a torque read from a table of the state."""

from __future__ import annotations

import jax.numpy as jnp

# Beyond the tables' last knot the knot coordinate grows by one every this many kelvin (rad/s of slip): steadily,
# so that no crossing is missed, and slowly, so that the whole numbers it passes there (no knots) are 1e6 apart.
BEYOND_THE_TABLE = 1e6  # K


def knots_passed(value, knots):
    """A table's knots counted along its argument (a temperature, a slip speed's size, >= 0): a whole number
    exactly at each knot, rising steadily with the argument everywhere (below the first knot, -1 at zero)."""
    inside = jnp.interp(value, knots, jnp.arange(knots.shape[0], dtype=knots.dtype))
    below = (value - knots[0]) / jnp.where(knots[0] > 0.0, knots[0], 1.0)  # (none below a first knot at zero)
    above = knots.shape[0] - 1 + (value - knots[-1]) / BEYOND_THE_TABLE
    return jnp.where(value < knots[0], below, jnp.where(value > knots[-1], above, inside))

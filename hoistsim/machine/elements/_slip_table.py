"""A friction read from a table of the slip speed: Modelica's mu_pos and tau_pos, the same either way of slip."""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from ._knots import interpolate, knots_passed


def slip_columns(table, values: str) -> dict:
    """An element's fields for a table of the slip speed (rows [speed, value]): ``slip_speeds`` and ``values``,
    and ``slip_varies``; none for a constant (``table`` None)."""
    if table is None:
        return {}
    speeds, read = (np.asarray(column, float) for column in zip(*table))
    return {"slip_speeds": speeds, values: read, "slip_varies": True}


def along_slip(x, section: str, speeds, values):
    """The table's value at the size of the coupling's slip speed (flat beyond its rows)."""
    return interpolate(jnp.abs(x.relative_speed(section)), speeds, values)


def slip_knots(x, section: str, speeds):
    """The table's knots counted along the size of the slip speed: whole at each, so no step straddles one."""
    return knots_passed(jnp.abs(x.relative_speed(section)), speeds)

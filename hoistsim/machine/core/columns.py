"""What a run shows: the elements' output columns at rows, and their summary values at the end."""

from __future__ import annotations

import jax
import jax.numpy as jnp

from .dynamics import Instant
from .schedule import table_at, tables_of


def row_outputs(plan, times, states, modes):
    """Every element's output columns at rows (times, states, modes), stacked (columns, rows)."""
    layout = plan.layout
    tables = tables_of(plan.elements)
    names = list(layout.columns())

    def table(name, t):
        return table_at(*tables[name], t)

    def one(t, y, m):
        x = Instant(layout, t, y, m, table)
        out = {}
        for element in layout.elements:
            out.update(element.outputs(x))
        out.update({layout.angle_columns[shaft][0]: x.angle(shaft) for shaft in layout.angle_shafts})
        return jnp.stack([jnp.asarray(out[name], dtype=jnp.float64) for name in names])

    return jax.vmap(one, out_axes=1)(times, states, modes)


def summary_values(plan, extremes: dict, y, modes) -> list:
    """The summary values in the order the elements declare them: running reductions and end values."""
    tables = tables_of(plan.elements)
    x = Instant(plan.layout, plan.duration, y, modes, lambda name, t: table_at(*tables[name], t))
    values = dict(extremes)
    for element in plan.layout.elements:
        values.update(element.summary(x))
    return [jnp.asarray(values[name], dtype=jnp.float64) for name in plan.layout.summaries]

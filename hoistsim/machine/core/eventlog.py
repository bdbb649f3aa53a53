"""The run's event log: one buffer of rows, written once per event, read back into its fields."""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp

# The event log's fields before the state and the modes: time, kind, element, torque margin.
LOG_FIELDS = 4


def record(c, when, t, kind, element, y, modes, margin=jnp.nan):
    """Append an event row to the loop's carry ``c`` when ``when`` holds (a masked write: branch-free).

    One row of one buffer: under vmap a write to a buffer indexed by a per-lane
    count costs as much as the buffer, so one write beats one per field, and a
    summary-only run keeps a log of one row and counts the events by kind.
    """
    i = jnp.minimum(c.log_count, c.log.shape[0] - 1)
    # a lean log (summary-only runs) keeps no state: its rows are never output rows
    state = y if c.log.shape[1] > LOG_FIELDS + modes.shape[0] else y[:0]
    row = jnp.concatenate([jnp.stack([jnp.asarray(v, jnp.float64) for v in (t, kind, element, margin)]),
                           state, modes.astype(jnp.float64)])
    log = c.log.at[i].set(jnp.where(when, row, c.log[i]))
    counts = c.kind_counts + (when & (jnp.arange(c.kind_counts.shape[0]) == kind))
    return eqx.tree_at(lambda k: (k.log_count, k.kind_counts, k.log), c, (c.log_count + when, counts, log))


def unpack(log, count, couplings: int, columns: bool):
    """The log's fields: times, torque margins, (kind, element) codes, states, modes (-1 past ``count``)."""
    logged = jnp.arange(log.shape[0]) < count
    codes = jnp.where(logged[:, None], log[:, 1:3], -1.0).astype(jnp.int32)
    state = log[:, LOG_FIELDS: -couplings or None] if columns else jnp.zeros((log.shape[0], 0))
    modes = jnp.where(logged[:, None], log[:, log.shape[1] - couplings:], -1.0).astype(jnp.int32)
    return log[:, 0], log[:, 3], codes, state, modes

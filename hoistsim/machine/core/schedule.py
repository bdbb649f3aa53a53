"""Piecewise-linear tables of time and the segments between scheduled boundaries.

A table's knots (kinks and steps) and every element's scheduled times are
segment boundaries: the integration stops and restarts there instead of
searching for them, so each table is one straight line over a segment.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp

from ..._pytree import pytree_dataclass


def table_at(times, values, t, xp=jnp):
    """Piecewise-linear value, right-continuous at steps; ``xp`` is numpy or jax.numpy.

    Works for scalar or array ``t`` and for tables with repeated times (steps):
    the interval used is the last one that starts at or before ``t``.  Before
    the first time the first value holds, after the last the last.
    """
    t = xp.asarray(t)
    n = times.shape[0]
    if n == 1:
        return xp.broadcast_to(values[0], t.shape) * xp.ones_like(t)
    k = xp.clip(xp.searchsorted(times, t, side="right") - 1, 0, n - 2)
    t0, t1 = times[k], times[k + 1]
    f0, f1 = values[k], values[k + 1]
    width = t1 - t0
    safe = xp.where(width > 0, width, 1.0)
    # within [0, 1) wherever it is used (the interval holds t; outside the table its ends hold), so unclipped: its
    # derivative in t is the interval's slope, the right one at a knot (a signal's rate at a row there)
    frac = (t - t0) / safe
    value = xp.where(width > 0, f0 + frac * (f1 - f0), f1)
    value = xp.where(t < times[0], values[0], value)
    return xp.where(t >= times[-1], values[-1], value)


def tables_of(elements) -> dict:
    """Every table the elements declare: name -> (times, values) arrays."""
    return {name: (getattr(e, times), getattr(e, values))
            for e in elements for name, (times, values) in e.tables().items()}


@pytree_dataclass
class Segment:
    """What holds between two scheduled boundaries: each table is one line on it."""

    start: jax.Array  # s
    end: jax.Array  # s
    lines: dict  # table name -> (value at start, slope per second)

    @property
    def middle(self):
        return 0.5 * (self.start + self.end)

    def table(self, name, t):
        value, slope = self.lines[name]
        return value + slope * (t - self.start)

    def zero_throughout(self, name):
        """Whether a table is zero over the whole segment."""
        value, slope = self.lines[name]
        return (value == 0.0) & (value + slope * (self.end - self.start) == 0.0)


def _line(times, values, t0, middle):
    """(value at t0, slope) of the table interval holding ``middle``.

    The interval that holds the middle of the segment gives its line, so a step
    at either end of the segment belongs to the neighbouring segment.
    """
    if times.shape[0] == 1:
        return values[0], jnp.zeros_like(values[0])
    k = jnp.clip(jnp.searchsorted(times, middle, side="right") - 1, 0, times.shape[0] - 2)
    width = times[k + 1] - times[k]
    inside = (middle >= times[0]) & (middle < times[-1]) & (width > 0)
    slope = jnp.where(inside, (values[k + 1] - values[k]) / jnp.where(width > 0, width, 1.0), 0.0)
    start = jnp.where(inside, values[k] + slope * (t0 - times[k]), table_at(times, values, middle))
    return start, slope


def segment_from(elements, boundaries, duration, t0) -> Segment:
    """The segment starting at t0: it ends at the next boundary (or the duration)."""
    later = jnp.where(boundaries > t0, boundaries, duration)
    t1 = jnp.minimum(jnp.min(later), duration)
    middle = 0.5 * (t0 + t1)
    lines = {name: _line(times, values, t0, middle) for name, (times, values) in tables_of(elements).items()}
    return Segment(start=t0, end=t1, lines=lines)


def scheduled_times(elements) -> list:
    """Every boundary the elements schedule: their tables' knots and their own times."""
    times = [t for times, _ in tables_of(elements).values() for t in times]
    return times + [t for e in elements for t in e.boundaries()]

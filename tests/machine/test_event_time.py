"""An event time's derivative by the implicit function theorem, and none where the guard only grazes zero."""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import pytest

from hoistsim.machine.core.event_time import event_time


def _located(guard, p, start=0.0, end=3.0):
    """The guard's first zero in (start, end] by bisection, the guard at or below zero at ``end`` (as at a
    step's end where it crossed), through event_time (the bisection carries no derivative of its own)."""
    def below(t):
        return guard(t, p) <= 0.0

    lo, hi = start, end
    for _ in range(200):
        middle = 0.5 * (lo + hi)
        lo, hi = jax.lax.cond(below(middle), lambda: (lo, middle), lambda: (middle, hi))
    return event_time(jax.lax.stop_gradient(hi), lambda t, x: guard(t, x), start, p)


def test_a_crossing_moves_as_the_implicit_function_theorem_says():
    # g = p^2 - t^2: crosses at t* = p, dt*/dp = 1; g = p - t^3 crosses at p^(1/3)
    for guard, p, expected in ((lambda t, p: p * p - t * t, 1.3, 1.0),
                               (lambda t, p: p - t ** 3, 2.0, (1 / 3) * 2.0 ** (-2 / 3))):
        t, slope = jax.jvp(lambda q: _located(guard, q), (jnp.asarray(p),), (jnp.asarray(1.0),))
        assert float(slope) == pytest.approx(expected, rel=1e-10)


def test_a_guard_that_only_touches_zero_has_no_derivative():
    # g = (t - p)^2 - 1e-16 dips below zero by round-off's width (roots p -+ 1e-8): a slip that just reaches
    # zero; a little less dip and there is no crossing at all
    t, slope = jax.jvp(lambda q: _located(lambda t, p: (t - p) ** 2 - 1e-16, q, end=1.2), (jnp.asarray(1.2),),
                       (jnp.asarray(1.0),))
    assert abs(float(t) - 1.2) < 1e-6 and math.isnan(float(slope))
    # a shallow crossing that is still one (a dip of 1e-4: roots 0.01 apart) keeps its derivative, 1
    t, slope = jax.jvp(lambda q: _located(lambda t, p: (t - p) ** 2 - 1e-4, q, end=1.2), (jnp.asarray(1.2),),
                       (jnp.asarray(1.0),))
    assert float(slope) == pytest.approx(1.0, rel=1e-9)


def test_the_value_is_the_bisections():
    guard = lambda t, p: p - t  # noqa: E731
    assert float(_located(guard, jnp.asarray(0.7))) == float(jax.jit(lambda q: _located(guard, q))(0.7))


def test_a_guard_that_steps_below_zero_as_the_step_begins_moves_with_the_start():
    # at a table's knot p the guard jumps from above zero to below: the instant is the knot, dt*/dp = 1
    def jumped(q):
        return _located(lambda t, p: jnp.where(t > p, -5.0 + 0.1 * t, 3.0 + t), q, start=q, end=q + 1.0)

    t, slope = jax.jvp(jumped, (jnp.asarray(1.2),), (jnp.asarray(1.0),))
    assert abs(float(t) - 1.2) < 1e-12 and float(slope) == 1.0

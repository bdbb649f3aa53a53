"""What a run is given and how it may end: the plan's traced inputs, the statuses of a finished run.

Apart from the loop (:mod:`.loop`) so that building a plan and reading a run
never import the solver library: a run whose program is already compiled
needs only these.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

from ..._pytree import pytree_dataclass
from .layout import Layout

OK, CHATTERING, SOLVER_FAILED, TOO_MANY_SEGMENTS = range(4)
STATUS_TEXT = {OK: "ok", CHATTERING: "chattering", SOLVER_FAILED: "solver failed",
               TOO_MANY_SEGMENTS: "too many segments"}

# Passes that may end at a kink, per allowed switch (beyond, kinks are stepped across).
KINK_BUDGET = 100


@pytree_dataclass
class Plan:
    """Everything one run needs, as arrays: the traced inputs of the compiled loop."""

    elements: tuple
    boundaries: jax.Array  # s, scheduled segment boundaries (any order, within [0, duration])
    initial_state: jax.Array  # named by Layout(elements).state_names
    speed_scale: jax.Array  # rad/s, for the slip resolution
    duration: jax.Array  # s
    grid: jax.Array  # s, output times (padded with the duration)
    rtol: jax.Array
    atol: jax.Array
    max_switches: jax.Array  # mode switches allowed before the run counts as chattering

    @property
    def layout(self) -> Layout:
        """Where its elements' states, bodies and columns sit: worked out whenever asked (some 60 us), never
        kept on the plan (a plan is frozen, and JAX makes plans of placeholders and of one trace's values)."""
        return Layout(self.elements)


def expected_cycles(plan: Plan, xp=np):
    """The cycles a machine with a period of its own (a cycle angle) is expected to turn in the run: as many as
    its fastest speed scale turns in the duration, twice over, rounded up to a power of two; 0 for a machine
    without.  ``xp``: numpy for the loop's static sizes, jax.numpy inside the loop (the plan's values traced)."""
    periods = [xp.asarray(e.cycle_angle()) for e in plan.elements if e.cycles]
    if not periods:
        return 0
    turned = plan.duration * xp.maximum(xp.maximum(plan.speed_scale, xp.abs(plan.initial_state[0])), 1.0)
    return xp.exp2(xp.ceil(xp.log2(xp.maximum(2.0 * turned / xp.min(xp.stack(periods)) + 8, 1.0))))


def segment_budget(plan: Plan) -> jax.Array:
    """The passes a run may take before it stops as "too many segments", traced: each ends at a boundary, a
    switch or an observation (as many allowed as switches) or a kink (KINK_BUDGET per switch), per expected
    cycle for a machine with cycles.  Traced, so that a new max_switches, duration or speed compiles nothing."""
    kinks = KINK_BUDGET * plan.max_switches if any(e.kink_names() for e in plan.elements) else 0
    per_cycle = 2 * plan.max_switches + kinks
    return plan.boundaries.shape[0] + 2 + per_cycle + expected_cycles(plan, jnp) * per_cycle

"""What a run is given and how it may end: the plan's traced inputs, the statuses of a finished run.

Apart from the loop (:mod:`.loop`) so that building a plan and reading a run
never import the solver library: a run whose program is already compiled
needs only these.
"""

from __future__ import annotations

import jax

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

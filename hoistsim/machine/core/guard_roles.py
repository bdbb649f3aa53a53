"""The guards as one vector: the roles its places hold, as constant masks, and the knots' slopes where a pass
starts.

A pass reads every guard at once (:func:`.switching.guard_values`, in the order of :func:`.switching.guards`);
what the loop does with them afterwards (which ended the pass, which restart lowered, which crossed along with
the located one) is a few operations on that vector with these masks, not one a guard: XLA copies a scalar
that many such operations read into each of them, and the program grew as the guards times the couplings.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

from .guard_id import SLIP, GuardId, knot_guards
from .layout import Layout


def of_role(guards, role: str) -> np.ndarray:
    """Which guards have ``role`` ("switch", "observe", "limit", "valley", "kink")."""
    return np.array([r == role for r, _, _ in guards])


def lowerable(guards) -> np.ndarray:
    """Which guards restart at their own zero, lowered by their value there when one ended a pass (see
    switching): the observations, limits and valleys."""
    return of_role(guards, "observe") | of_role(guards, "limit") | of_role(guards, "valley")


def reported(guards, events=frozenset()) -> np.ndarray:
    """The guards whose crossing along with the located one :func:`.switching.crossed_together` reports: the
    couplings' slip zeros, the knots, the limits and the observations that are events."""
    switch = of_role(guards, "switch")
    slip = np.array([name.kind == SLIP for _, name, _ in guards]) & switch
    event = np.array([name in events for _, name, _ in guards]) & ~switch
    return slip | event | of_role(guards, "kink") | of_role(guards, "limit")


def bends(guards) -> jax.Array | None:
    """Which guards are a table's knots, where the rate bends (None: the machine has none)."""
    kinks = of_role(guards, "kink")
    return jnp.asarray(kinks) if kinks.any() else None


def passed_over(layout: Layout, guards) -> np.ndarray | None:
    """Which guards are knots that a pass steps over rather than ends at: every table's knot but a cycle's end
    (the period of a periodic regime, an event of its own).  Nothing jumps at a knot, and nothing is decided
    there: a pass that ended at each paid the whole restart (the decision's inputs, the anchors, the guards read
    afresh) for two steps' worth of motion, the engine hoist 14 000 times in a run.  None: the machine has none."""
    cycle_ends = {name for index, kink, _ in layout.cycles for name in knot_guards(layout.sections[index], kink)}
    mask = of_role(guards, "kink") & np.array([name not in cycle_ends for _, name, _ in guards])
    return mask if mask.any() else None


def knot_partners(layout: Layout, guards) -> np.ndarray:
    """For each guard, the place of the other guard of its knot coordinate (the knot ahead's partner is the knot
    behind, and the other way round); any other guard's, its own place."""
    place = {name: i for i, (_, name, _) in enumerate(guards)}
    partner = np.arange(len(guards))
    for element in layout.elements:
        for kink in element.kink_names():
            ahead, behind = (place[name] for name in knot_guards(element.section, kink))
            partner[ahead], partner[behind] = behind, ahead
    return partner


def bend_slopes(layout: Layout, guards, anchors: dict, kinking) -> jax.Array | None:
    """The knots' guards' rates where the pass starts, from the knot coordinates' own (the anchors): the guard of
    the knot ahead falls as the coordinate rises, the one behind rises with it (the others: zero, unread)."""
    rates = {}
    for element in layout.elements:
        for kink in element.kink_names():
            ahead, behind = knot_guards(element.section, kink)
            rate = anchors[GuardId(element.section, kink)][1]
            rates[ahead], rates[behind] = -rate, rate
    if not rates:
        return None
    return jnp.stack([jnp.where(kinking, rates[name], 0.0) if name in rates else jnp.zeros(())
                      for _, name, _ in guards])

"""The run's running reductions: each element's extremes, first times and durations, folded in as the loop goes.

Every extremum is a row (a guard ends a pass where a value peaks), so folding the state at each row and each
pass's end into a running max, min or first time gives the exact value, not a sample's.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp

from .dynamics import Instant
from .element import STUCK
from .layout import Layout

# the core's own running reduction: the most kinetic energy held at a row or a pass's end (the energy
# ledger's scale where the works cancel over the run and the machine ends as it started)
KINETIC_PEAK = "kinetic_energy_peak"

# each kind's value before anything is folded in (its identity: -inf for a max, NaN for a first time...)
_STARTS = {"max": -jnp.inf, "min": jnp.inf, "first": jnp.nan, "first_value": jnp.nan, "duration": 0.0}


def reductions(layout: Layout, x: Instant) -> dict:
    """name -> (kind, value at x) of every running reduction: the core's and each element's."""
    out = {KINETIC_PEAK: ("max", x.kinetic_energy())}
    for element in layout.elements:
        out.update(element.extremes(x))
    return out


def folded(extremes: dict, layout: Layout, x: Instant) -> tuple[dict, dict]:
    """The running reductions with the machine at ``x`` folded in; and whether each duration's condition holds
    there (it holds over the pass that starts there)."""
    out, holding = {}, {}
    for name, (kind, value) in reductions(layout, x).items():
        if kind == "duration":
            holding[name] = value
        old = extremes[name]
        if kind == "max":
            out[name] = jnp.maximum(old, value)
        elif kind == "min":
            out[name] = jnp.minimum(old, value)
        elif kind == "first":
            out[name] = jnp.where(jnp.isnan(old) & value, x.t, old)
        elif kind == "first_value":
            out[name] = jnp.where(jnp.isnan(old) & value[0], value[1], old)
        else:  # a duration: added up over the passes it holds in (loop._step)
            out[name] = old
    return out, holding


def initial_extremes(layout: Layout, initial_state) -> dict:
    """Each running reduction's starting value."""
    kinds = {}

    def probe(state):  # traced apart (eval_shape): the kinds are wanted, not the values
        x = Instant(layout, jnp.zeros(()), state, jnp.full((len(layout.couplings),), STUCK),
                    lambda name, t: jnp.zeros(()))
        kinds.update({name: kind for name, (kind, _) in reductions(layout, x).items()})
        return jnp.zeros(())

    jax.eval_shape(probe, initial_state)
    return {name: jnp.asarray(_STARTS[kind], dtype=jnp.float64) for name, kind in kinds.items()}

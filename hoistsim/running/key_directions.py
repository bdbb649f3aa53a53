"""A key's direction in a run's inputs: the derivative of the plan (the elements' numbers) with respect to a
scenario key, from plans built at values either side of it (a central difference, extrapolated once: exact
to round-off where the plan is linear or quadratic in the key, as it is in a mass, an inertia, a friction
coefficient or a force).  A key whose change would change the machine's structure (which elements, their
tables' lengths) has no derivative and is refused."""

from __future__ import annotations

import dataclasses

import jax
import numpy as np

from .._pytree import static_values
from ..errors import ScenarioError
from ..machine.assemble import build_plan
from ..scenario.keys import check_key
from ..scenario.loading import Scenario
from ..scenario.sweep_spec import held_at, with_swept_value

# The relative step of the plan's central difference (extrapolated once: its error is of the order of the
# step to the fourth power times the plan's fifth derivative in the key, and round-off / step).
PLAN_STEP = 1e-3


def key_value(scenario: Scenario, key: str, option: str = "--wrt") -> float:
    """The SI number a key holds; for a force table, its largest force (the table scaled with it)."""
    check_key(key, option, scenario.provenance.raw)
    held = _held(scenario, key, option)
    if hasattr(held, "forces"):
        return float(max(held.forces, key=abs))
    if type(held) is int:  # a count (teeth, surfaces): it moves in whole steps
        raise ScenarioError(f"{option} {key}", f"is a count ({held}), a whole number: it has no derivative")
    if isinstance(held, bool) or not isinstance(held, (int, float)):
        raise ScenarioError(f"{option} {key}", f"holds {held!r}, not a number: a derivative is taken with "
                                               "respect to a number")
    return float(held)


def is_table(scenario: Scenario, key: str) -> bool:
    """Whether ``key`` holds a force table of several rows (its number: the largest force, the rest scaled)."""
    return len(getattr(held_at(scenario, key), "forces", ())) > 1


def value_to_set(scenario: Scenario, key: str, x: float):
    """The value to give ``key`` for its number to be ``x``: a force table's rows with every force scaled by
    x over its largest (its shape kept; the times as they are)."""
    held = _held(scenario, key, "--wrt")
    if not hasattr(held, "forces"):
        return x
    peak = float(max(held.forces, key=abs))
    if peak == 0.0:
        raise ScenarioError(f"--wrt {key}", "is a table of no force: there is no force to scale")
    return [[t, f * (x / peak)] for t, f in zip(held.times, held.forces)]


def _held(scenario: Scenario, key: str, option: str = "--wrt"):
    held = held_at(scenario, key)
    if held is None:
        raise ScenarioError(f"{option} {key}", "is not set in this scenario: a derivative is taken where a "
                                               "value is given")
    return held


def plan_direction(scenario: Scenario, key: str, x: float, plan, option: str = "--wrt"):
    """The derivative of ``plan`` (the scenario's, on any output grid) with respect to ``key`` at ``x``: the
    direction of the run's inputs the key moves them in (integer leaves: none)."""
    h = PLAN_STEP * (abs(x) or 1.0)
    base, structure = jax.tree.flatten(plan)
    statics, shapes = static_values(plan), [np.shape(leaf) for leaf in base]

    def leaves_at(offset: float):
        moved, _ = build_plan(with_swept_value(scenario, key, value_to_set(scenario, key, x + offset)),
                              summary_only=True)
        moved = dataclasses.replace(moved, grid=plan.grid)  # the key does not move the output times
        leaves, moved_structure = jax.tree.flatten(moved)
        leaves = [np.asarray(leaf) for leaf in leaves]
        if moved_structure != structure or static_values(moved) != statics or [a.shape for a in leaves] != shapes:
            raise ScenarioError(f"{option} {key}", "changes the machine's structure near its value (which "
                                                   "elements, a table's rows): it has no derivative here")
        return leaves

    return jax.tree.unflatten(structure, extrapolated(base, [leaves_at(offset) for offset in offsets(h)], h))


def offsets(h: float) -> tuple[float, ...]:
    """Where the plans either side of a key's value are built, for :func:`extrapolated`."""
    return h, -h, h / 2, -h / 2


def extrapolated(base: list, moved: list[list], h: float) -> list:
    """The leaves of a plan's derivative from its leaves ``moved`` to the :func:`offsets` of ``h``: the central
    differences at h and h/2, extrapolated once; integer leaves (``base``'s) have none (float0)."""
    def quotient(up, down, step):  # a leaf the key leaves as it is (an infinite limit too) does not move
        with np.errstate(invalid="ignore"):  # inf - inf, where np.where does not take it
            return [np.zeros(a.shape) if a.tobytes() == b.tobytes() else np.where(a == b, 0.0, (a - b) / step)
                    for a, b in zip(up, down)]

    wide = quotient(moved[0], moved[1], 2 * h)
    half = quotient(moved[2], moved[3], h)
    return [np.zeros(np.shape(leaf), jax.dtypes.float0) if np.asarray(leaf).dtype.kind != "f"
            else (4 * n - w) / 3 for leaf, w, n in zip(base, wide, half)]


def stacked_directions(scenario: Scenario, keys: list[str], values: dict, plan, option: str = "--wrt"):
    """Each key's :func:`plan_direction`, stacked on a leading axis (one a key)."""
    directions = [plan_direction(scenario, key, values[key], plan, option) for key in keys]
    return jax.tree.map(lambda *leaves: np.stack(leaves), *directions)

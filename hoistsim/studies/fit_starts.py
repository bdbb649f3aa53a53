"""Where a fit starts: the fitted keys' ranges swept, every starting point a run of one compiled, vectorised call.

Levenberg-Marquardt only walks downhill from where it starts, and a start can
hide the answer: a load too heavy for the clutch to lock leaves the motor's
speed independent of the load (the slipping clutch passes the same torque
whatever it drives), so the Jacobian's column of the load's mass is zero there
and the fit cannot move it.  So the keys' ranges are swept first: ``count``
points spread over them (a scrambled Halton sequence, seeded: the same points
every time), each run at the measured times through the sweep's compiled loop
(:func:`hoistsim.running.blocks.compiled_batch`, one program for every chunk),
and the fit starts from the point whose run meets the trace best, or from the
scenario's own values where none does better.

A key's range: ``--range KEY=LO:HI`` where given; else its ``--bounds``; else
what a real part's value lies in (the schema's plausible range, a load's 1 kg
to 1000 t); else a third to three times the scenario's value.  Each is held
within the key's bounds and the schema's limits; a range of more than a decade
from above zero is swept evenly in its logarithm.
"""

from __future__ import annotations

import dataclasses
import functools
import math

import jax
import numpy as np

from .. import _jax
from .._pytree import static_values
from ..errors import ScenarioError
from ..machine.assemble import build_plan, log_rows, step_room
from ..machine.core.plan import OK
from ..machine.core.readout import KEPT_STEPS, STATUS
from ..running.blocks import compiled_batch, devices_for
from ..running.simulation import read_layout
from ..scenario.keys import field_at
from ..scenario.plausible import Plausible
from ..scenario.units import Limits, dimension_of, metadata_of, to_si

# Starting points a fit sweeps by default, and the runs of one compiled call (a power of two: one shape).
STARTS = 256
CHUNK = 64
# A range this many times its low end or wider is swept evenly in its logarithm.
DECADE = 10.0


@dataclasses.dataclass
class SweptStart:
    """The sweep of starting points: how many were run, the best's values and cost against the scenario's own."""

    count: int  # points swept (the scenario's own values not counted)
    ran: int  # of them, the runs that completed (a point the scenario refuses is not run)
    ranges: dict[str, tuple[float, float]]  # key -> (low, high) swept, in SI; a key held at its value absent
    values: np.ndarray  # the start chosen: the best point, or the scenario's values where none did better
    cost: float  # its weighted sum of squared residuals
    cost_at_scenario: float  # the same at the scenario's values

    @property
    def moved(self) -> bool:
        return self.cost < self.cost_at_scenario


def key_ranges(scenario_values: np.ndarray, keys: list[str], ranges: dict, low: np.ndarray,
               high: np.ndarray) -> dict[str, tuple[float, float]]:
    """Each key's range to sweep (see the module's text), in SI; a key without one (a value of zero with no
    range given) is left out: it starts at its value."""
    out = {}
    for k, key in enumerate(keys):
        span = ranges.get(key)
        if span is None and math.isfinite(low[k]) and math.isfinite(high[k]):
            span = (low[k], high[k])
        if span is None:
            span = _plausible(key, scenario_values[k]) or _around(scenario_values[k])
        if span is None:
            continue
        lo, hi = _within_limits(key, *span)
        lo, hi = max(lo, low[k]), min(hi, high[k])
        if lo < hi:
            out[key] = (lo, hi)
    return out


def _plausible(key: str, value: float) -> tuple[float, float] | None:
    """What a real part's value of the key lies in, on the side of zero ``value`` is (a plausible range holds
    sizes)."""
    field = field_at(key)
    plausible = metadata_of(field, Plausible) if field is not None else None
    if plausible is None:
        return None
    dimension = dimension_of(field)
    lo, hi = to_si(plausible.low, dimension), to_si(plausible.high, dimension)
    return (-hi, -lo) if value < 0 else (lo, hi)


def _around(value: float) -> tuple[float, float] | None:
    """A third to three times ``value`` (of either sign); None for zero, which has no scale."""
    if value == 0:
        return None
    return tuple(sorted((value / 3.0, value * 3.0)))


def _within_limits(key: str, lo: float, hi: float) -> tuple[float, float]:
    """``lo``, ``hi`` held within the schema's limits of the key (a friction coefficient above zero); an open
    limit is kept off by a part in a million of the range."""
    field = field_at(key)
    limits = metadata_of(field, Limits) if field is not None else None
    if limits is None:
        return lo, hi
    margin = 1e-6 * (hi - lo)
    for value, open_ in ((limits.ge, False), (limits.gt, True)):
        if value is not None:
            lo = max(lo, value + (margin if open_ else 0.0))
    for value, open_ in ((limits.le, False), (limits.lt, True)):
        if value is not None:
            hi = min(hi, value - (margin if open_ else 0.0))
    return lo, hi


def sweep_points(keys: list[str], scenario_values: np.ndarray, ranges: dict, count: int) -> np.ndarray:
    """``count`` points (rows) over the keys' ranges, a key without a range at its scenario value: a scrambled
    Halton sequence, seeded, so that the same fit sweeps the same points."""
    from scipy.stats import qmc

    swept = [k for k, key in enumerate(keys) if key in ranges]
    points = np.tile(np.asarray(scenario_values, dtype=float), (count, 1))
    if not swept:
        return points
    unit = qmc.Halton(d=len(swept), scramble=True, seed=0).random(count)
    for column, k in enumerate(swept):
        lo, hi = ranges[keys[k]]
        u = unit[:, column]
        points[:, k] = lo * (hi / lo) ** u if lo > 0 and hi >= DECADE * lo else lo + (hi - lo) * u
    return points


def best_start(model, scenario_values: np.ndarray, ranges: dict, count: int, cost_of) -> SweptStart:
    """The sweep's best start (see the module's text): ``model`` a fit's model of the run (its ``scenario_at``
    and ``trace``), ``cost_of`` ({column: rows at the measured times}) -> the fit's cost."""
    points = sweep_points(model.keys, scenario_values, ranges, count)
    candidates = np.vstack([scenario_values, points])
    costs = _costs(model, candidates, cost_of)
    best = int(np.argmin(costs))  # the scenario's own values (row 0) win a tie
    if not math.isfinite(costs[0]):
        raise ScenarioError("--fit", "the run fails at the scenario's own values: fix the scenario first")
    return SweptStart(count=count, ran=int(np.sum(np.isfinite(costs[1:]))), ranges=dict(ranges),
                      values=candidates[best], cost=float(costs[best]), cost_at_scenario=float(costs[0]))


def _costs(model, candidates: np.ndarray, cost_of) -> np.ndarray:
    """The fit's cost of each candidate's run (inf where the scenario refuses the values, the run fails, or its
    plan is shaped unlike the scenario's own and so cannot share the compiled call)."""
    costs = np.full(len(candidates), np.inf)
    plans, lanes = [], []
    signature, named = None, None
    for k, values in enumerate(candidates):
        try:
            scenario = model.scenario_at(values)
        except ScenarioError:
            continue
        plan, _ = build_plan(scenario, summary_only=True)
        plan = dataclasses.replace(plan, grid=model.trace.grid())
        leaves, structure = jax.tree.flatten(plan)
        shape = (structure, static_values(plan), [np.shape(leaf) for leaf in leaves])
        if signature is None:
            signature, named = shape, scenario
        if shape == signature:
            plans.append(plan)
            lanes.append(k)
    layout = read_layout(plans[0], named) if plans else None
    for offset in range(0, len(plans), CHUNK):
        chunk = plans[offset:offset + CHUNK]
        for lane, found in zip(lanes[offset:offset + CHUNK], _run_chunk(chunk, model.solver, layout, model)):
            if found is not None:
                cost = cost_of(found)
                costs[lane] = cost if math.isfinite(cost) else math.inf
    return costs


def _run_chunk(plans: list, solver: str, layout, model) -> list:
    """Each plan's matched columns at the measured times ({column: rows}, None where its run failed): the chunk
    padded to CHUNK runs with its last (one compiled shape), run as one vectorised call; taken again with
    room for more steps where a run kept more than the call had room for."""
    stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *plans, *[plans[-1]] * (CHUNK - len(plans)))
    devices = devices_for(CHUNK)
    sizes = (log_rows(plans[0]), step_room(plans[0]))
    m = model.trace.time.size
    while True:
        run = _jax.executable(functools.partial(compiled_batch, solver, *sizes, True, devices), stacked,
                              name=f"fit-starts-{solver}-{sizes}", devices=devices)
        raw = jax.device_get(run(stacked))
        kept = int(np.max(raw.counters[: len(plans), KEPT_STEPS]))
        if kept <= sizes[1]:
            break
        sizes = (sizes[0], step_room(plans[0], kept))
    status = raw.counters[: len(plans), STATUS]
    rows = np.asarray(raw.grid_columns)
    return [{name: rows[k, layout.column_slot(name), :m] for name in model.match} if status[k] == OK else None
            for k in range(len(plans))]

"""Keys fitted to a measured trace: least squares with the exact Jacobian, through every switch.

The run is evaluated at the measured times (its output grid is the trace's
times) and differentiated forward along each fitted key at once, as
:mod:`hoistsim.running.sensitivity` differentiates summaries: the Jacobian of
every matched series at every measured time is exact, switches included (a
lock or a breakaway that moves past measured rows moves them with it).

Levenberg-Marquardt on the residuals, each matched column divided by its
measured range so that columns of different units weigh alike, the keys
scaled by their starting values; bounds (``KEY=LO:HI``) hold each key by
projection, and a step the scenario refuses (a kinetic friction above the
static) is a rejected step.  At the optimum: the residual variance
s^2 = |r|^2 / (m - n), the covariance s^2 (J^T J)^-1, each key's standard error
and its 95 % interval from Student's t with m - n degrees of freedom.

Before it the keys' ranges are swept (:mod:`.fit_starts`): a start where the
trace cannot see a key (its Jacobian column zero) would leave that key where it
is.  After it, a key the trace does not determine gets no interval, and
residuals far from the noise or patterned are said to be so
(:mod:`.fit_checks`).
"""

from __future__ import annotations

import dataclasses
import functools
import math

import numpy as np

from ..errors import ScenarioError
from ..machine.assemble import build_plan
from ..machine.core.plan import OK
from ..running.derivative_program import differentiated
from ..running.key_directions import key_value, stacked_directions, value_to_set
from ..running.simulation import read_layout
from ..scenario.keys import key_units
from ..scenario.loading import Scenario
from ..scenario.sweep_spec import with_swept_value
from .fit_checks import NOT_SEEN, ResidualCheck, residual_check, residual_warnings, undetermined
from .fit_starts import STARTS, SweptStart, best_start, key_ranges
from .measured_trace import Trace, read_trace

MAX_ITERATIONS = 60
# converged: the cost's relative fall, and each step relative to its key, below these
COST_RTOL, STEP_RTOL = 1e-10, 1e-9


@dataclasses.dataclass
class FitResult:
    """The fitted keys (SI), their standard errors and 95 % intervals (None for a key the trace does not
    determine), the residuals and what they say, and the fitted run."""

    keys: list[str]
    start: dict[str, float]  # where Levenberg-Marquardt started: the sweep's best, or the scenario's values
    values: dict[str, float]
    standard_errors: dict[str, float | None]
    intervals: dict[str, tuple[float, float] | None]
    key_units: dict[str, str]
    residual_rms: dict[str, float]  # column -> RMS of measured - fitted, in the series' units
    trace: Trace
    fitted: dict[str, np.ndarray]  # column -> the fitted run at the measured times (series' units)
    scenario: Scenario  # the scenario with the fitted values
    iterations: int
    converged: bool
    correlation: np.ndarray  # between the fitted keys (NaN for an undetermined one)
    at_start: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)  # the run at the scenario's values
    given: dict[str, float] = dataclasses.field(default_factory=dict)  # the scenario's values
    undetermined: dict[str, str] = dataclasses.field(default_factory=dict)  # key -> why the trace does not
    checks: dict[str, ResidualCheck] = dataclasses.field(default_factory=dict)  # column -> its residuals' check
    swept: SweptStart | None = None  # the sweep of starting points, where there was one
    warnings: list[str] = dataclasses.field(default_factory=list)

    @property
    def sound(self) -> bool:
        """Converged, every key determined, and the residuals the noise."""
        return self.converged and not self.warnings

    def to_dict(self) -> dict:
        """``{key: {"value": v, "standard_error": s, "interval_95": [lo, hi], "determined": yes}, "rms": r,
        "residuals": {series: {...}}, "warnings": [...]}`` in SI: ``r`` the RMS of every matched series'
        residuals, each in its series' SI unit; an undetermined key's error and interval null."""
        pooled = [self.fitted[name] - self.trace.columns[name] for name in self.fitted]
        keys = {key: {"value": self.values[key], "standard_error": self.standard_errors[key],
                      "interval_95": None if self.intervals[key] is None else list(self.intervals[key]),
                      "determined": key not in self.undetermined} for key in self.keys}
        return {**keys, "rms": float(np.sqrt(np.mean(np.concatenate(pooled) ** 2))),
                "residuals": {name: check.to_dict() for name, check in self.checks.items()},
                "warnings": list(self.warnings)}


def fit(scenario: Scenario, measured, match: list[str], keys: list[str],
        bounds: dict[str, tuple[float, float]] | None = None, ranges: dict[str, tuple[float, float]] | None = None,
        starts: int = STARTS) -> FitResult:
    """Fit ``keys`` (dotted scenario keys holding numbers) so that the run's series ``match`` meet the trace
    ``measured`` (a CSV path, see :mod:`.measured_trace`, or a :class:`Trace`) at its times; ``bounds``: key
    -> (low, high) in SI; ``ranges``: key -> (low, high) in SI, where ``starts`` starting points are swept
    (:mod:`.fit_starts`; 0: from the scenario's values alone)."""
    if scenario.sweep:
        raise ScenarioError("sweep", "a fit is of one run: remove the sweep")
    if not keys:
        raise ScenarioError("--fit", "name at least one key to fit, like --fit clutch.kinetic_friction")
    if not match:
        raise ScenarioError("--match", "name at least one series to match, like --match motor_speed")
    plan, _ = build_plan(scenario, summary_only=True)
    columns = read_layout(plan, scenario).columns()
    for name in match:
        if name not in columns:
            raise ScenarioError("--match", f"no series {name!r} in this scene; it has {', '.join(columns)}")
    trace = measured if isinstance(measured, Trace) else read_trace(
        measured, match, {name: units for name, (units, _) in columns.items()}, float(scenario.simulation.duration))
    given = np.array([key_value(scenario, key, "--fit") for key in keys])
    low, high = _bounds(keys, bounds or {}, "--bounds")
    if np.any((given < low) | (given > high)):
        k = int(np.flatnonzero((given < low) | (given > high))[0])
        raise ScenarioError(f"--bounds {keys[k]}",
                            f"the scenario's value {given[k]:g} is outside {low[k]:g}:{high[k]:g}")
    _bounds(keys, ranges or {}, "--range")
    if trace.time.size <= len(keys):
        raise ScenarioError("--measured", f"{trace.time.size} measured times cannot fit {len(keys)} keys",
                            source=trace.source)
    model = _Model(scenario, keys, trace, match)
    weights = np.array([1.0 / _spread(trace.columns[name]) for name in match])

    def cost_of(rows) -> float:
        return float(sum(np.sum(((rows[name] - trace.columns[name]) * w) ** 2) for name, w in zip(match, weights)))

    def residuals(values):
        rows, jacobian = model(values)
        if rows is None:
            return None, None
        r = np.concatenate([(rows[name] - trace.columns[name]) * w for name, w in zip(match, weights)])
        j = np.concatenate([jacobian[name] * w for name, w in zip(match, weights)])
        return r, j

    swept = None
    if starts > 0:
        spans = key_ranges(given, keys, ranges or {}, low, high)
        swept = best_start(model, given, spans, starts, cost_of) if spans else None
    start = swept.values if swept is not None else given
    at_start, _ = model(given)
    scale = np.where(start != 0, np.abs(start), 1.0)
    values, r, j, iterations, converged = _levenberg_marquardt(residuals, start, scale, low, high)
    values, r, j = _unseen_given_back(residuals, values, r, j, given, keys)
    reasons = undetermined(j, values, keys)
    seen = np.array([key not in reasons for key in keys])
    m, n = r.size, len(keys)
    variance = float(r @ r) / (m - n)
    covariance = np.full((n, n), np.nan)
    if np.any(seen):
        information = j[:, seen].T @ j[:, seen]
        covariance[np.ix_(seen, seen)] = variance * np.linalg.pinv(information)
    errors = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    from scipy.stats import t as student

    spread = float(student.ppf(0.975, m - n))
    rows, _ = model(values)
    checks = {name: residual_check(trace.columns[name] - rows[name]) for name in match}
    with np.errstate(invalid="ignore", divide="ignore"):
        correlation = covariance / np.outer(errors, errors)
    warnings = [f"{key}: {why}: undetermined" for key, why in reasons.items()]
    for name, check in checks.items():
        warnings += residual_warnings(name, check, functools.partial(_amount, trace, name))
    if not converged:
        warnings.append(f"not converged after {iterations} iterations: the values are where the fit stopped")
    return FitResult(
        keys=list(keys), start=dict(zip(keys, start.tolist())), values=dict(zip(keys, values.tolist())),
        standard_errors={key: None if key in reasons else float(e) for key, e in zip(keys, errors)},
        intervals={key: None if key in reasons else (v - spread * e, v + spread * e)
                   for key, v, e in zip(keys, values, errors)},
        key_units={key: key_units(key) or "1" for key in keys},
        residual_rms={name: check.rms for name, check in checks.items()}, trace=trace, fitted=rows,
        scenario=model.scenario_at(values), iterations=iterations, converged=converged, correlation=correlation,
        at_start=at_start or {}, given=dict(zip(keys, given.tolist())), undetermined=reasons, checks=checks,
        swept=swept, warnings=warnings)


def _amount(trace: Trace, name: str, value: float) -> str:
    """An amount (a difference) of a matched series, in SI, as text in the unit the trace writes it in."""
    shown = float(trace.shown(name, value) - trace.shown(name, 0.0))
    return f"{shown:.3g} {trace.written[name]}"


def _unseen_given_back(residuals, values, r, j, given, keys):
    """Keys the trace does not see at the optimum (a zero column) back at the scenario's values where that
    leaves the residuals as they are: the sweep's start put them anywhere in their ranges, and nothing in
    the trace says where."""
    reasons = undetermined(j, values, keys)
    unseen = [k for k, key in enumerate(keys) if reasons.get(key) == NOT_SEEN and values[k] != given[k]]
    if not unseen:
        return values, r, j
    trial = values.copy()
    trial[unseen] = given[unseen]
    r_new, j_new = residuals(trial)
    if r_new is None or float(r_new @ r_new) > float(r @ r) * (1 + 1e-9) + 1e-300:
        return values, r, j
    return trial, r_new, j_new


def _spread(values: np.ndarray) -> float:
    """A column's scale: its measured range (1 where it has none)."""
    spread = float(np.max(values) - np.min(values))
    return spread if spread > 0 else max(float(np.max(np.abs(values))), 1.0)


def _bounds(keys: list[str], bounds: dict, option: str) -> tuple[np.ndarray, np.ndarray]:
    """Each key's (low, high) of ``bounds`` (or of ``--range``), unbounded where not given."""
    for key in bounds:
        if key not in keys:
            raise ScenarioError(f"{option} {key}", f"is not a fitted key ({', '.join(keys)})")
    low = np.array([bounds.get(key, (-math.inf, math.inf))[0] for key in keys], dtype=float)
    high = np.array([bounds.get(key, (-math.inf, math.inf))[1] for key in keys], dtype=float)
    if np.any(low >= high):
        k = int(np.flatnonzero(low >= high)[0])
        raise ScenarioError(f"{option} {keys[k]}", f"the low end {low[k]:g} is not below the high {high[k]:g}")
    return low, high


def _levenberg_marquardt(residuals, start, scale, low, high):
    """(values, residuals, Jacobian, iterations, converged) from ``start``: Marquardt's damping on the scaled
    keys, each step projected into the bounds; a step whose run fails (None) or costs more is rejected."""
    x = start.copy()
    r, j = residuals(x)
    if r is None:
        raise ScenarioError("--fit", "the run fails at the scenario's own values: fix the scenario first")
    cost, damping = float(r @ r), 1e-3
    for iteration in range(1, MAX_ITERATIONS + 1):
        js = j * scale  # d r / d (x / scale)
        a, g = js.T @ js, js.T @ r
        while True:
            step = -np.linalg.solve(a + damping * np.diag(np.maximum(np.diag(a), 1e-12)), g) * scale
            trial = np.clip(x + step, low, high)
            r_new, j_new = residuals(trial)
            new_cost = float(r_new @ r_new) if r_new is not None else math.inf
            if new_cost < cost:
                break
            damping *= 10.0
            if damping > 1e12:  # no step lowers the cost: at the optimum, to round-off
                return x, r, j, iteration, True
        fell = (cost - new_cost) / cost if cost > 0 else 0.0
        moved = np.max(np.abs(trial - x) / scale)
        x, r, j, cost, damping = trial, r_new, j_new, new_cost, max(damping / 10.0, 1e-12)
        if fell < COST_RTOL or moved < STEP_RTOL:
            return x, r, j, iteration, True
    return x, r, j, MAX_ITERATIONS, False


class _Model:
    """The run's matched series at the measured times and their derivatives along each key, at given values
    (the last few kept: the fit asks again at its start and its optimum)."""

    def __init__(self, scenario: Scenario, keys: list[str], trace: Trace, match: list[str]):
        self.base, self.keys, self.trace, self.match = scenario, keys, trace, match
        self.solver = scenario.simulation.solver
        self.seen: dict[tuple, tuple] = {}

    def scenario_at(self, values) -> Scenario:
        run = self.base
        for key, x in zip(self.keys, values):
            run = with_swept_value(run, key, value_to_set(run, key, float(x)))
        return run

    def __call__(self, values):
        """({column: rows}, {column: (rows, keys) Jacobian}); (None, None) where the scenario refuses the
        values or the run fails."""
        key = tuple(float(x) for x in values)
        if key not in self.seen:
            if len(self.seen) > 8:
                self.seen.pop(next(iter(self.seen)))
            self.seen[key] = self._evaluated(key)
        return self.seen[key]

    def _evaluated(self, values):
        try:
            scenario = self.scenario_at(values)
        except ScenarioError:
            return None, None
        plan, _ = build_plan(scenario, summary_only=True)
        times = self.trace.time
        plan = dataclasses.replace(plan, grid=self.trace.grid())
        directions = stacked_directions(scenario, self.keys, dict(zip(self.keys, values)), plan, "--fit")
        layout = read_layout(plan, scenario)
        readout, _, tangents, _, _ = differentiated(plan, directions, scenario.simulation.solver, columns=True,
                                                    layout=layout)
        if readout.status != OK:
            return None, None
        rows = np.asarray(readout.raw.grid_columns)
        m = times.size
        found = {name: rows[layout.column_slot(name), :m] for name in self.match}
        jacobian = {name: np.asarray(tangents)[:, layout.column_slot(name), :m].T for name in self.match}
        return found, jacobian


def parse_ranges(items: list[str], option: str = "--bounds") -> dict[str, tuple[float, float]]:
    """``KEY=LO:HI`` (each end a number in the key's SI unit, or with its unit; several to an item, comma
    separated) -> {key: (lo, hi)} in SI."""
    from ..scenario.keys import field_at
    from ..scenario.units import UnitError, dimension_of, to_si

    out = {}
    for item in (part for given in items for part in _assignments(given)):
        key, sep, text = item.partition("=")
        ends = text.split(":")
        if not sep or len(ends) != 2:
            raise ScenarioError(option, f"expected KEY=LO:HI, like clutch.kinetic_friction=0.05:0.2, got {item!r}")
        field = field_at(key.strip())
        dimension = dimension_of(field) if field is not None else None
        try:
            lo, hi = (to_si(_number_or_text(end), dimension) if dimension is not None else float(end)
                      for end in ends)
        except (UnitError, ValueError) as exc:
            raise ScenarioError(f"{option} {key.strip()}", str(exc)) from None
        out[key.strip()] = (lo, hi)
    return out


def _assignments(text: str) -> list[str]:
    """``a=1:2,b=3 kg:4 kg`` -> the assignments; a comma not followed by a new ``KEY=`` stays in its value."""
    parts: list[str] = []
    for piece in text.split(","):
        if parts and "=" not in piece:
            parts[-1] += "," + piece
        else:
            parts.append(piece)
    return [part.strip() for part in parts if part.strip()]


def _number_or_text(text: str):
    try:
        return float(text)
    except ValueError:
        return text.strip()

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
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import ScenarioError
from ..machine.assemble import build_plan
from ..machine.core.plan import OK
from ..running.derivative_program import differentiated
from ..running.key_directions import key_value, stacked_directions, value_to_set
from ..scenario.keys import key_units
from ..scenario.loading import Scenario
from ..scenario.sweep_spec import with_swept_value
from .measured_trace import Trace, read_trace

MAX_ITERATIONS = 60
# converged: the cost's relative fall, and each step relative to its key, below these
COST_RTOL, STEP_RTOL = 1e-10, 1e-9


@dataclasses.dataclass
class FitResult:
    """The fitted keys (SI), their standard errors and 95 % intervals, the residuals, and the fitted run."""

    keys: list[str]
    start: dict[str, float]
    values: dict[str, float]
    standard_errors: dict[str, float]
    intervals: dict[str, tuple[float, float]]
    key_units: dict[str, str]
    residual_rms: dict[str, float]  # column -> RMS of measured - fitted, in the series' units
    trace: Trace
    fitted: dict[str, np.ndarray]  # column -> the fitted run at the measured times (series' units)
    scenario: Scenario  # the scenario with the fitted values
    iterations: int
    converged: bool
    correlation: np.ndarray  # between the fitted keys
    at_start: dict[str, np.ndarray] = dataclasses.field(default_factory=dict)  # the run at the starting values

    def to_dict(self) -> dict:
        """``{key: {"value": v, "standard_error": s, "interval_95": [lo, hi]}, "rms": r}`` in SI: ``r`` the RMS of
        every matched series' residuals, each in its series' SI unit."""
        pooled = [self.fitted[name] - self.trace.columns[name] for name in self.fitted]
        return {**{key: {"value": self.values[key], "standard_error": self.standard_errors[key],
                         "interval_95": list(self.intervals[key])} for key in self.keys},
                "rms": float(np.sqrt(np.mean(np.concatenate(pooled) ** 2)))}


def fit(scenario: Scenario, measured, match: list[str], keys: list[str],
        bounds: dict[str, tuple[float, float]] | None = None) -> FitResult:
    """Fit ``keys`` (dotted scenario keys holding numbers) so that the run's series ``match`` meet the trace
    ``measured`` (a CSV path, see :mod:`.measured_trace`, or a :class:`Trace`) at its times; ``bounds``: key
    -> (low, high) in SI."""
    if scenario.sweep:
        raise ScenarioError("sweep", "a fit is of one run: remove the sweep")
    if not keys:
        raise ScenarioError("--fit", "name at least one key to fit, like --fit clutch.kinetic_friction")
    if not match:
        raise ScenarioError("--match", "name at least one series to match, like --match motor_speed")
    plan, _ = build_plan(scenario, summary_only=True)
    columns = plan.layout.columns()
    for name in match:
        if name not in columns:
            raise ScenarioError("--match", f"no series {name!r} in this scene; it has {', '.join(columns)}")
    trace = measured if isinstance(measured, Trace) else read_trace(
        measured, match, {name: units for name, (units, _) in columns.items()}, float(scenario.simulation.duration))
    start = np.array([key_value(scenario, key, "--fit") for key in keys])
    low, high = _bounds(keys, bounds or {})
    if np.any((start < low) | (start > high)):
        k = int(np.flatnonzero((start < low) | (start > high))[0])
        raise ScenarioError(f"--bounds {keys[k]}", f"the scenario's value {start[k]:g} is outside {low[k]:g}:{high[k]:g}")
    if trace.time.size <= len(keys):
        raise ScenarioError("--measured", f"{trace.time.size} measured times cannot fit {len(keys)} keys",
                            source=trace.source)
    model = _Model(scenario, keys, trace, match)
    weights = np.array([1.0 / _spread(trace.columns[name]) for name in match])
    scale = np.where(start != 0, np.abs(start), 1.0)

    def residuals(values):
        rows, jacobian = model(values)
        if rows is None:
            return None, None
        r = np.concatenate([(rows[name] - trace.columns[name]) * w for name, w in zip(match, weights)])
        j = np.concatenate([jacobian[name] * w for name, w in zip(match, weights)])
        return r, j

    at_start, _ = model(start)
    values, r, j, iterations, converged = _levenberg_marquardt(residuals, start, scale, low, high)
    m, n = r.size, len(keys)
    variance = float(r @ r) / (m - n)
    covariance = variance * np.linalg.pinv(j.T @ j)
    errors = np.sqrt(np.maximum(np.diag(covariance), 0.0))
    from scipy.stats import t as student

    spread = float(student.ppf(0.975, m - n))
    rows, _ = model(values)
    rms = {name: float(np.sqrt(np.mean((rows[name] - trace.columns[name]) ** 2))) for name in match}
    with np.errstate(invalid="ignore", divide="ignore"):
        correlation = covariance / np.outer(errors, errors)
    return FitResult(
        keys=list(keys), start=dict(zip(keys, start.tolist())), values=dict(zip(keys, values.tolist())),
        standard_errors=dict(zip(keys, errors.tolist())),
        intervals={key: (v - spread * e, v + spread * e) for key, v, e in zip(keys, values, errors)},
        key_units={key: key_units(key) or "1" for key in keys}, residual_rms=rms, trace=trace, fitted=rows,
        scenario=model.scenario_at(values), iterations=iterations, converged=converged, correlation=correlation,
        at_start=at_start or {})


def _spread(values: np.ndarray) -> float:
    """A column's scale: its measured range (1 where it has none)."""
    spread = float(np.max(values) - np.min(values))
    return spread if spread > 0 else max(float(np.max(np.abs(values))), 1.0)


def _bounds(keys: list[str], bounds: dict) -> tuple[np.ndarray, np.ndarray]:
    for key in bounds:
        if key not in keys:
            raise ScenarioError(f"--bounds {key}", f"is not a fitted key ({', '.join(keys)})")
    low = np.array([bounds.get(key, (-math.inf, math.inf))[0] for key in keys], dtype=float)
    high = np.array([bounds.get(key, (-math.inf, math.inf))[1] for key in keys], dtype=float)
    if np.any(low >= high):
        k = int(np.flatnonzero(low >= high)[0])
        raise ScenarioError(f"--bounds {keys[k]}", f"the low end {low[k]:g} is not below the high {high[k]:g}")
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
        grid = np.concatenate([times, np.full(_padded_size(times.size) - times.size, times[-1])])
        plan = dataclasses.replace(plan, grid=grid)
        directions = stacked_directions(scenario, self.keys, dict(zip(self.keys, values)), plan, "--fit")
        readout, _, tangents, _, _ = differentiated(plan, directions, scenario.simulation.solver, columns=True)
        if readout.status != OK:
            return None, None
        rows = np.asarray(readout.raw.grid_columns)
        names = list(plan.layout.columns())
        m = times.size
        found = {name: rows[names.index(name), :m] for name in self.match}
        jacobian = {name: np.asarray(tangents)[:, names.index(name), :m].T for name in self.match}
        return found, jacobian


def _padded_size(count: int) -> int:
    return max(64, 1 << int(np.ceil(np.log2(count))))


def parse_bounds(items: list[str]) -> dict[str, tuple[float, float]]:
    """``KEY=LO:HI`` (each end a number in the key's SI unit, or with its unit) -> {key: (lo, hi)} in SI."""
    from ..scenario.keys import field_at
    from ..scenario.units import UnitError, dimension_of, to_si

    out = {}
    for item in items:
        key, sep, text = item.partition("=")
        ends = text.split(":")
        if not sep or len(ends) != 2:
            raise ScenarioError("--bounds", f"expected KEY=LO:HI, like clutch.kinetic_friction=0.05:0.2, got {item!r}")
        field = field_at(key.strip())
        dimension = dimension_of(field) if field is not None else None
        try:
            lo, hi = (to_si(_number_or_text(end), dimension) if dimension is not None else float(end)
                      for end in ends)
        except (UnitError, ValueError) as exc:
            raise ScenarioError(f"--bounds {key.strip()}", str(exc)) from None
        out[key.strip()] = (lo, hi)
    return out


def _number_or_text(text: str):
    try:
        return float(text)
    except ValueError:
        return text.strip()


def fitted_text(result: FitResult) -> str:
    """The scenario's text with each fitted key set to its fitted value (its unit written), comments kept."""
    import io

    from ..scenario.yamlsource import yaml_reader

    yaml = yaml_reader()
    tree = yaml.load(io.StringIO(result.scenario.provenance.text))
    for key in result.keys:
        node, *path = [tree, *key.split(".")]
        for part in path[:-1]:
            node = node[int(part)] if isinstance(node, list) else node[part]
        units = result.key_units[key]
        held = node[path[-1]]
        value = result.values[key]
        if isinstance(held, list):  # a force table: every force scaled as the fit scaled its largest
            node[path[-1]] = [[f"{t:.6g} s", f"{f:.6g} N"] for t, f in value_to_set(result.scenario, key, value)]
        else:
            node[path[-1]] = float(f"{value:.6g}") if units == "1" else f"{value:.6g} {units}"
    out = io.StringIO()
    yaml.dump(tree, out)
    return out.getvalue()


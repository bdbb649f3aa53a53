"""The clutch's temperature: the first-order response to the exact slip power, friction that fades with heat
(against an independent scipy integration), overheating as an exact event, the heat ledger, and the hard
cases where the temperature's events meet the clutch's own (a table knot, the limit, at the lock)."""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from helpers import EXERCISE6, reduced
from scipy.integrate import quad, solve_ivp
from scipy.optimize import brentq

from hoistsim import scenario_from_dict, simulate
from hoistsim.machine.core.layout import Layout
from hoistsim.machine.elements import elements_for
from hoistsim.references.exact import exact_from_scenario
from hoistsim.references.model import Machine

ZERO_CELSIUS = 273.15
# One structure for the constant-friction checks and one for the fading ones (three knots, a limit given),
# so that the module compiles two programs.
CONSTANT_HEATING = {"heat_capacity": "500 J/K", "cooling": "20 W/K", "ambient_temperature": "25 degC",
                    "initial_temperature": "60 degC", "max_temperature": "1500 degC"}
FADING = {"static_friction": [["25 degC", 0.3], ["35 degC", 0.25], ["60 degC", 0.15]],
          "kinetic_friction": [["25 degC", 0.1], ["35 degC", 0.085], ["60 degC", 0.05]]}


def heated(heating: dict, force="6000 N", motor_speed="300 rpm", duration="1 s", **simulation):
    """The exercise-6 hoist engaged at speed (the drum at rest) with ``clutch_heating:``."""
    data = copy.deepcopy(EXERCISE6)
    data["clutch"]["engagement_force"] = force
    data["initial"] = {"motor_speed": motor_speed}
    data["simulation"].update({"duration": duration, **simulation})
    data["clutch_heating"] = {**CONSTANT_HEATING, **heating}
    return scenario_from_dict(data, name="heated")


def first_order_temperature(exact, times, spec) -> np.ndarray:
    """C dT/dt = P(t) - G (T - T_amb) for the closed form's slip power P, solved exactly:
    T(t) = T_amb + (T_0 - T_amb) e^(-t/tau) + (1/C) int_0^t P(s) e^(-(t-s)/tau) ds, tau = C/G, the
    integral by adaptive quadrature piece by piece (P is smooth between the closed form's switches)."""
    capacity, conductance = spec.heat_capacity, spec.cooling
    ambient, start = spec.ambient_temperature, spec.start_temperature
    switches = [e.time for e in exact.events if 0.0 < e.time]
    out = []
    for t in np.atleast_1d(times):
        edges = [0.0, *[s for s in switches if s < t], t]
        heat = sum(quad(lambda s: exact.slip_power(s)[0] * math.exp(-(t - s) * conductance / capacity), a, b,
                        epsabs=0.0, epsrel=1e-13, limit=200)[0] for a, b in zip(edges[:-1], edges[1:]) if b > a)
        out.append(ambient + (start - ambient) * math.exp(-t * conductance / capacity) + heat / capacity)
    return np.asarray(out)


def reference(scenario, rtol=1e-12):
    """An independent integration of the two-shaft hoist with its clutch's temperature and friction tables
    (scipy DOP853, event restarts at a lock, a breakaway and every knot of the tables).  A constant force from
    t = 0, the drum at rest, the clutch slipping at the start.  Returns (lock times, evaluate(ts) ->
    rows of motor speed, pinion speed, temperature)."""
    d = Machine.from_scenario(scenario).reduced()
    spec = scenario.clutch_heating
    force = scenario.clutch.engagement_force.forces[0]
    temps = sorted({row[0] for table in (spec.static_friction, spec.kinetic_friction) for row in table})

    def mu(table, temperature):
        return np.interp(temperature, [r[0] for r in table], [r[1] for r in table])

    ja, jb, tl = d.motor_inertia, d.output_inertia, d.load_torque
    capacity, conductance, ambient = spec.heat_capacity, spec.cooling, spec.ambient_temperature

    def locked(y):
        acceleration = (d.motor_torque(y[0]) - tl) / (ja + jb)
        return d.motor_torque(y[0]) - ja * acceleration, acceleration

    def rhs(t, y, mode):
        cooling = conductance * (y[2] - ambient)
        if mode == 0:
            _, acceleration = locked(y)
            return [acceleration, acceleration, -cooling / capacity]
        torque = mode * mu(spec.kinetic_friction, y[2]) * d.clutch_constant * force
        power = torque * (y[0] - y[1])
        return [(d.motor_torque(y[0]) - torque) / ja, (torque - tl) / jb, (power - cooling) / capacity]

    t, y, mode = 0.0, np.array([scenario.initial.motor_speed, 0.0, spec.start_temperature]), 1
    pieces, locks, duration = [], [], scenario.simulation.duration
    while t < duration:
        events = [lambda t, y, *_, k=k: y[2] - k for k in temps if abs(y[2] - k) > 1e-9 * k]
        for event in events:
            event.terminal = True
        if mode == 0:
            def breakaway(t, y, *_):
                return mu(spec.static_friction, y[2]) * d.clutch_constant * force - abs(locked(y)[0])
            breakaway.terminal, breakaway.direction = True, -1
            events.append(breakaway)
        else:
            def slip(t, y, *_, s=mode):
                return s * (y[0] - y[1])
            slip.terminal, slip.direction = True, -1
            events.append(slip)
        sol = solve_ivp(rhs, (t, duration), y, method="DOP853", rtol=rtol, atol=1e-12, args=(mode,),
                        events=events, dense_output=True)
        pieces.append((t, sol.t[-1], sol.sol))
        t, y = sol.t[-1], sol.y[:, -1].copy()
        if sol.status != 1 or t >= duration:
            break
        fired = next(i for i, te in enumerate(sol.t_events) if len(te))
        if fired == len(events) - 1:  # the clutch's own event
            if mode == 0:
                mode = 1 if locked(y)[0] > 0 else -1
            else:
                y[0] = y[1] = (ja * y[0] + jb * y[1]) / (ja + jb)
                held = abs(locked(y)[0]) <= mu(spec.static_friction, y[2]) * d.clutch_constant * force
                mode = 0 if held else mode
                locks.append(t) if held else None

    def evaluate(ts):
        return np.stack([next(p for p in pieces[::-1] if p[0] <= tq)[2](tq) for tq in ts], axis=1)

    return locks, evaluate


def _instants(run, kind):
    return run.instants["time"][run.instants["kind"] == kind]


@pytest.fixture(scope="module")
def engaged():
    """The canonical engagement at speed (6000 N at 300 rpm: slips 0.207 s, then locks), its closed form,
    and the first-order response of its temperature at every row (the grid and the exact instants)."""
    s = heated({})
    run = simulate(s)
    exact = exact_from_scenario(s)
    return s, run, exact, first_order_temperature(exact, run.time, s.clutch_heating)


def test_temperature_is_the_first_order_response_to_the_exact_slip_power(engaged):
    s, run, exact, expected = engaged
    got = run.series["clutch_temperature"]
    rise = expected.max() - expected.min()
    assert rise > 0.5  # K: a check worth making
    assert np.max(np.abs(got - expected)) < 1e-8 * rise
    # the friction is constant: the heat changes nothing of the motion
    assert run.lockup_time == pytest.approx(exact.lockup_time, abs=1e-9)
    # the peak is a row (where the slip power falls to the cooling), the summary's peak exact
    peak = _instants(run, "temperature_peak")
    assert len(peak) == 1 and peak[0] < exact.lockup_time
    fine = np.linspace(peak[0] - 1e-3, peak[0] + 1e-3, 41)
    assert run.values["peak_clutch_temperature"] == pytest.approx(
        first_order_temperature(exact, fine, s.clutch_heating).max(), abs=1e-8 * rise)
    assert np.isnan(run.values["overheat_time"])


def test_without_cooling_the_temperature_is_the_slip_energy_over_the_heat_capacity():
    s = heated({"cooling": "0 W/K"})
    run = simulate(s)
    spec = s.clutch_heating
    expected = spec.start_temperature + exact_from_scenario(s).evaluate(run.time)["clutch_energy"] / spec.heat_capacity
    assert np.max(np.abs(run.series["clutch_temperature"] - expected)) < 1e-8 * (expected[-1] - expected[0])
    assert run.values["peak_clutch_temperature"] == pytest.approx(expected[-1], rel=1e-12)


def test_heat_stored_and_passed_to_ambient_is_the_slip_energy(engaged):
    _, run, _, _ = engaged
    balance = run.energy_balance
    assert balance["clutch_heat_to_ambient"] > 0.05 * balance["clutch_energy"]  # both terms matter here
    assert abs(balance["heat_residual"]) < 1e-8 * balance["clutch_energy"]
    assert run.summary["heat_relative_residual"] < 1e-8
    assert balance["relative_residual"] < 1e-8
    spec = run.scenario.clutch_heating
    stored = (run.series["clutch_temperature"] - spec.start_temperature) * spec.heat_capacity
    np.testing.assert_allclose(run.series["clutch_energy"], stored + run.series["clutch_heat_to_ambient"],
                               rtol=0, atol=1e-8 * balance["clutch_energy"])


def test_an_absent_section_adds_nothing():
    data = copy.deepcopy(EXERCISE6)
    layout = Layout(elements_for(scenario_from_dict(data, name="cold")))
    assert not [n for n in layout.state_names if "temperature" in n or "ambient" in n]
    assert "clutch_temperature" not in layout.columns() and "peak_clutch_temperature" not in layout.summaries
    assert "heat of clutch_energy" not in layout.ledger_kinds.values()
    clutch = next(e for e in layout.elements if e.section == "clutch")
    assert not clutch.fades and clutch.kink_names() == ()
    # without a limit, no overheat guard and no overheat summary
    unlimited = {k: v for k, v in CONSTANT_HEATING.items() if k != "max_temperature"}
    data["clutch_heating"] = unlimited
    layout = Layout(elements_for(scenario_from_dict(data, name="warm")))
    assert "clutch_temperature" in layout.state_names and "overheat_time" not in layout.summaries
    from hoistsim.machine.core.switching import guards
    assert not [name for _, name, _ in guards(layout) if name.endswith("overheat")]


# ---------------------------------------------------------------------------------------------------------
# friction that fades with heat


def test_constant_tables_leave_every_speed_unchanged(engaged):
    _, plain, _, _ = engaged
    constant = {"static_friction": [["0 degC", 0.3], ["200 degC", 0.3], ["400 degC", 0.3]],
                "kinetic_friction": [["0 degC", 0.1], ["200 degC", 0.1], ["400 degC", 0.1]]}
    run = simulate(heated(constant))
    assert run.scenario.clutch_heating.fades
    for column in ("motor_speed", "drum_speed", "clutch_temperature", "clutch_torque"):
        np.testing.assert_allclose(run.series[column], plain.series[column], rtol=1e-12, atol=1e-12)
    assert run.lockup_time == pytest.approx(plain.lockup_time, abs=1e-12)


@pytest.fixture(scope="module")
def fading():
    """Friction fading from 0.3/0.1 at 25 degC to 0.15/0.05 at 60 degC, a small clutch heated hard: the
    lock comes later than at constant friction, after the temperature has crossed a knot."""
    s = heated({**FADING, "heat_capacity": "60 J/K", "initial_temperature": "25 degC"})
    return s, simulate(s), reference(s)


def test_fading_friction_matches_an_independent_integration(fading):
    s, run, (locks, evaluate) = fading
    constant = exact_from_scenario(heated({})).lockup_time
    assert len(locks) == 1 and locks[0] > constant + 0.01  # the fade delays the lock
    assert run.lockup_time == pytest.approx(locks[0], abs=1e-8)
    expected = evaluate(run.time)
    assert expected[2].max() > 35 + ZERO_CELSIUS  # past the middle knot
    np.testing.assert_allclose(run.series["motor_speed"], expected[0], rtol=0, atol=1e-8 * expected[0].max())
    np.testing.assert_allclose(run.series["pinion_speed"] if "pinion_speed" in run.series else
                               run.series["drum_speed"] * reduced(run).ratio, expected[1], rtol=0,
                               atol=1e-8 * expected[0].max())
    rise = expected[2].max() - expected[2].min()
    np.testing.assert_allclose(run.series["clutch_temperature"], expected[2], rtol=0, atol=1e-8 * rise)
    # the capacity reads the fade: the static friction at the temperature, times c F
    capacity = run.series["clutch_capacity"]
    mu = np.interp(run.series["clutch_temperature"], *zip(*s.clutch_heating.static_friction))
    np.testing.assert_allclose(capacity, mu * reduced(run).clutch_constant * 6000.0, rtol=1e-12)
    assert run.summary["heat_relative_residual"] < 1e-8 and run.summary["energy_relative_residual"] < 1e-8


def test_fade_that_keeps_a_clutch_from_ever_locking():
    """At constant friction this clutch locks at 0.21 s; its kinetic friction falls to a fifth by 60 degC,
    the torque it passes no longer lifts the load and it slips to the end."""
    strong = {"static_friction": [["25 degC", 0.3], ["40 degC", 0.12], ["60 degC", 0.06]],
              "kinetic_friction": [["25 degC", 0.1], ["40 degC", 0.04], ["60 degC", 0.02]],
              "heat_capacity": "40 J/K", "initial_temperature": "25 degC"}
    s = heated(strong)
    run = simulate(s)
    locks, evaluate = reference(s)
    assert exact_from_scenario(heated({})).lockup_time < 0.25
    assert locks == [] and np.isnan(run.lockup_time) and run.summary["lock_events"] == 0
    expected = evaluate(run.time)
    np.testing.assert_allclose(run.series["motor_speed"], expected[0], rtol=0, atol=1e-8 * expected[0].max())
    assert run.series["load_position"][-1] < 0  # the load runs back
    assert run.summary["heat_relative_residual"] < 1e-8 and run.summary["energy_relative_residual"] < 1e-8


# ---------------------------------------------------------------------------------------------------------
# hard cases: the temperature's events at the clutch's lock


def _lock_temperature(heating: dict):
    """The canonical engagement's lock-up time and its temperature there (the first-order closed form)."""
    s = heated(heating)
    exact = exact_from_scenario(s)
    return float(exact.lockup_time), float(first_order_temperature(exact, [exact.lockup_time], s.clutch_heating)[0])


def test_a_table_knot_crossed_exactly_at_the_lock():
    """A hot clutch cooling fast (150 degC, 200 W/K): its temperature falls through the tables' last knot
    exactly as it locks.  Above that knot the friction is the canonical 0.3 / 0.1, so the lock comes at the
    closed form's time; below it the clutch grips harder and stays locked: one lock, nothing after it."""
    cooling = {"initial_temperature": "150 degC", "cooling": "200 W/K"}
    lockup, knot = _lock_temperature(cooling)
    tables = {"static_friction": [[knot - 60, 0.36], [knot - 30, 0.33], [knot, 0.3]],
              "kinetic_friction": [[knot - 60, 0.12], [knot - 30, 0.11], [knot, 0.1]]}
    run = simulate(heated({**cooling, **tables}))
    assert run.lockup_time == pytest.approx(lockup, abs=1e-9)
    assert run.summary["lock_events"] == 1 and run.summary["unlock_events"] == 0
    at_lock = run.time == run.lockup_time
    assert run.series["clutch_temperature"][at_lock][0] == pytest.approx(knot, abs=1e-8 * (423.15 - knot))
    after = run.time > lockup + 0.1
    assert (run.series["clutch_temperature"][after] < knot - 1.0).all()  # well below the knot: gripping harder
    assert (run.series["clutch_capacity"][after] > 1.01 * run.series["clutch_capacity"][at_lock][0]).all()
    assert run.summary["heat_relative_residual"] < 1e-8


@pytest.mark.parametrize("offset", [-1e-3, -1e-6, 0.0, 1e-6], ids=["limit below", "limit just below",
                                                                  "limit at the lock", "limit just above"])
def test_overheat_at_the_lock(offset):
    """A clutch below ambient (0 degC in 80 degC air, 400 W/K) still warming as it locks, the limit set to
    its temperature at the lock (the closed form): one overheat row, at the lock; a limit a micro- or a
    milli-kelvin either side: just before or just after it (in the step that holds the lock, which diffrax
    would locate first), never lost and never twice."""
    warming = {"initial_temperature": "0 degC", "ambient_temperature": "80 degC", "cooling": "400 W/K"}
    lockup, limit = _lock_temperature(warming)
    s = heated({**warming, "max_temperature": limit + offset})
    run = simulate(s)
    exact = exact_from_scenario(s)
    crossing = brentq(lambda t: first_order_temperature(exact, [t], s.clutch_heating)[0] - limit - offset,
                      lockup - 1e-3, lockup + 1e-3, xtol=1e-15) if offset else lockup
    overheat = _instants(run, "overheat")
    assert run.lockup_time == pytest.approx(lockup, abs=1e-9)
    assert len(overheat) == 1
    assert overheat[0] == pytest.approx(crossing, abs=1e-10)
    assert run.values["overheat_time"] == overheat[0] and run.summary["lock_events"] == 1


def test_a_bare_temperature_is_kelvin_and_said():
    data = copy.deepcopy(EXERCISE6)
    data["clutch_heating"] = {**CONSTANT_HEATING, "ambient_temperature": 298,
                              "kinetic_friction": [[25, 0.1], ["60 degC", 0.08]]}
    s = scenario_from_dict(data, name="bare")
    assert s.clutch_heating.ambient_temperature == 298.0
    assert s.clutch_heating.kinetic_friction[0] == (25.0, 0.1)
    said = " | ".join(s.warnings)
    assert "clutch_heating.ambient_temperature: the bare number 298 is read as 298 K (24.85 degC)" in said
    assert "clutch_heating.kinetic_friction: row 1: the bare number 25 is read as 25 K (-248.15 degC)" in said


def test_the_closed_form_refuses_friction_that_fades():
    with pytest.raises(ValueError, match="clutch_heating's friction tables"):
        exact_from_scenario(heated(FADING))


@pytest.mark.slow
def test_the_duty_cycle_warms_the_clutch_start_by_start():
    """The shipped duty cycle: six starts 3 s apart, the pawl holding the load between.  Each start finds the
    clutch warmer, its friction lower and its lock-up later; the sixth passes the limit; the load only rises."""
    from helpers import SCENARIOS

    from hoistsim import load_scenario

    run = simulate(load_scenario(SCENARIOS / "clutch_duty_cycle.yaml"))
    rows = run.instants
    clutch = rows["element"] == "clutch"
    engages = rows["time"][clutch & (rows["kind"] == "engage")]
    locks = rows["time"][clutch & (rows["kind"] == "lock")]
    assert len(engages) == len(locks) == 6
    assert np.all(np.diff(locks - engages) > 0.05)  # each lock-up at least 50 ms later than the last
    at_engage = np.interp(engages, run.time, run.series["clutch_temperature"])
    assert np.all(np.diff(at_engage) > 5.0)  # K: the clutch starts each time warmer
    overheat = _instants(run, "overheat")
    assert len(overheat) == 1 and engages[5] < overheat[0] < locks[5]
    assert run.values["overheat_time"] == overheat[0]
    assert np.all(np.diff(run.series["load_position"]) > -1e-12)  # held by the pawl between starts
    assert run.summary["heat_relative_residual"] < 1e-10 and run.summary["energy_relative_residual"] < 1e-8

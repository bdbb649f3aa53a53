"""A mass's hard stops (drivetrain.stops) and a friction on a line with a Stribeck curve (drivetrain.bearing_frictions
on a mass): Modelica's MassWithStopAndFriction and SupportFriction.

- Friction (scenarios/modelica/translational/) within 1e-3 of each comparison signal's range at every reference row;
  HeatLosses so until its block first reaches its stop (after it, Dymola's reference keeps a spring-damper's relative
  speed through the stop's impact, stopping the mass behind the block with it: the test shows it in the reference).
- Closed forms: a ball bouncing on a floor with a coefficient of restitution (its impacts' instants, its coming to
  rest after finitely many, the impacts' loss its whole fall); a block sliding to rest under a Stribeck curve (the
  instant and the distance by quadrature); a block pushed into its stop, then pulled off it (the stop lets go where
  the push falls through zero, the friction where the pull reaches its static force).
- A block bouncing between two stops with a Stribeck friction against an independent integration (its friction
  turned round at each rebound).
- The ledger closes in every run, with the impacts' losses.
- Bad input: a stop on the wrong side of the start, stops crossed, a stop on no mass, a shaft's key on a line's
  friction, a Stribeck curve on a table: one line naming the key, nothing written.
- New values (a restitution, a stop's place, a Stribeck curve's numbers) compile nothing.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import SCENARIOS, part_keys_set, refused_in_one_line
from modelica_reference import deviations, events, reference, signals
from scipy.integrate import quad, solve_ivp

from hoistsim import load_scenario, scenario_from_dict, simulate
from hoistsim.references.modelica_signals import HEAT_LOSSES_FIRST_IMPACT

FOLDER = SCENARIOS / "modelica" / "translational"
# HeatLosses' block (massWithStopAndFriction) first reaches its upper stop here (Dymola's event; ours within 1e-7 s)
FIRST_IMPACT = HEAT_LOSSES_FIRST_IMPACT


@pytest.fixture(scope="module")
def runs():
    return {example: simulate(load_scenario(FOLDER / f"{example}.yaml")) for example in ("Friction", "HeatLosses")}


def test_friction_against_dymolas_published_trajectories(runs):
    """Stribeck friction from a curve and from a table of it, and stop2 run into its lower stop on a spring: each
    signal within 1e-3 of its range (measured: 4.7e-5 at worst, stop2's velocity); the ledger closes, stop2's impact
    taking its 18.6 J."""
    run = runs["Friction"]
    worst = deviations(run, "translational/Friction", signals("translational/Friction", run))
    assert max(worst.values()) < 1e-3, worst
    assert run.summary["stop2_ends_lower_impact_loss"] == pytest.approx(0.5 * 1.0 * 6.106**2, rel=1e-3)
    assert run.summary["energy_relative_residual"] < 1e-8
    times, kinds = run.instants["time"], list(run.instants["kind"])
    assert times[kinds.index("stop_reached")] == pytest.approx(events(reference("translational/Friction")["time"])[0],
                                                              abs=1e-6)


def test_heat_losses_against_dymolas_trajectories_until_its_block_reaches_its_stop(runs):
    """Every signal within 1e-3 of its range up to the block's first impact on its stop (measured: 6e-5 at worst but
    springDamper1.v_rel, the stiff spring-damper's relative speed, 6.8e-4).  After
    it, Dymola's trajectory keeps the stiff spring-damper's relative speed through the impact (Modelica's SpringDamper
    prefers it as a state, and the stop resets the block's speed alone): mass3 stops with the block there, where
    hoistsim's runs on into the damper (the physics of the parts: no impulse passes a spring-damper).  The signals
    then differ by up to 0.7 of their ranges (springDamper1's), 5e-3 (springDamper's)."""
    run = runs["HeatLosses"]
    table = reference("translational/HeatLosses")
    times = table["time"]
    worst = deviations(run, "translational/HeatLosses", signals("translational/HeatLosses", run),
                       until=FIRST_IMPACT)
    assert max(worst.values()) < 1e-3, worst
    impact = np.flatnonzero((times[1:] == times[:-1]) & (np.abs(times[1:] - FIRST_IMPACT) < 1e-5))[0]
    jump = table["massWithStopAndFriction.v"][impact + 1] - table["massWithStopAndFriction.v"][impact]
    assert jump == pytest.approx(-0.677, abs=1e-3)  # the block stopped
    assert table["springDamper1.v_rel"][impact + 1] == table["springDamper1.v_rel"][impact]  # mass3 with it
    kinds, instants = list(run.instants["kind"]), run.instants["time"]
    assert instants[kinds.index("stop_reached")] == pytest.approx(FIRST_IMPACT, abs=1e-6)
    assert run.summary["energy_relative_residual"] < 1e-8


def test_a_block_resting_against_its_stop_reaches_it_only_where_it_arrives(runs):
    """HeatLosses' block, pulled off its upper stop, is held there by its friction (its gap closed, its speed nil)
    until the friction breaks away at another switch: a stop is reached only after the block has come away from
    it, so the rows alternate reached, left, reached, left (measured: 0.4285 s, 0.7483 s, 1.4992 s, 1.7486 s)."""
    run = runs["HeatLosses"]
    kinds, times = np.asarray(run.instants["kind"]), run.instants["time"]
    stop_rows = np.isin(kinds, ("stop_reached", "stop_left"))
    assert list(kinds[stop_rows]) == ["stop_reached", "stop_left"] * 2
    upper = load_scenario(FOLDER / "HeatLosses.yaml").drivetrain.stops["stops"].upper
    position = run["massWithStopAndFriction_position"]
    for start, reached in zip(np.concatenate([[0.0], times[kinds == "stop_left"]]), times[kinds == "stop_reached"]):
        between = (run.time > start) & (run.time < reached)
        assert upper - position[between].min() > 1e-3  # it came from away from the stop


def _block(mass=1.0, position=0.0, velocity=0.0, force=((0.0, 0.0), (10.0, 0.0)), lower=-10.0, upper=10.0,
           restitution=0.0, rest_speed=1e-3, coulomb=0.0, stribeck=0.0, decay=0.0, viscous=0.0, peak=1.0,
           duration=3.0):
    """A block between two stops, pushed by a table of time, with a Stribeck friction: one program for every value."""
    return simulate(scenario_from_dict({"name": "block", "drivetrain": {
        "masses": {"block": {"mass": f"{mass} kg", "position": f"{position} m", "velocity": f"{velocity} m/s"}},
        "forces": [{"mass": "block", "force": [[f"{t} s", f"{f} N"] for t, f in force]}],
        "stops": {"ends": {"mass": "block", "lower": f"{lower} m", "upper": f"{upper} m", "restitution": restitution,
                           "rest_speed": f"{rest_speed} m/s"}},
        "bearing_frictions": {"friction": {"between": ["block", "ground"], "force": f"{coulomb} N",
                                           "stribeck": f"{stribeck} N", "decay": f"{decay} s/m",
                                           "viscous": f"{viscous} N*s/m", "peak": peak}}},
        "simulation": {"duration": f"{duration} s", "output_interval": "1 ms", "rtol": 1e-11, "atol": 1e-13}}))


def test_a_ball_bounces_on_its_floor_as_its_closed_form():
    """2 kg dropped from 1 m onto a floor with e = 0.5: it meets the floor at sqrt(2 h / g), and each rebound at e
    times the speed it came at flies 2 e v / g; a rebound slower than 1 cm/s (the ninth, 4.43 m/s 0.5^9) rests
    instead, after 8 rebounds.  The impacts' losses are the whole fall, m g h, the ledger closing."""
    g, height, e = 9.81, 1.0, 0.5
    run = _block(mass=2.0, position=height, force=((0.0, -2.0 * g), (10.0, -2.0 * g)), lower=0.0, restitution=e,
                 rest_speed=0.01)
    kinds, times = np.asarray(run.instants["kind"]), run.instants["time"]
    hits = times[(kinds == "stop_rebound") | (kinds == "stop_reached")]
    speed = math.sqrt(2 * g * height)
    expected = math.sqrt(2 * height / g) + np.concatenate([[0.0], np.cumsum(2 * speed * e ** np.arange(1, 9) / g)])
    assert list(kinds[(kinds == "stop_rebound") | (kinds == "stop_reached")]) == ["stop_rebound"] * 8 + ["stop_reached"]
    np.testing.assert_allclose(hits, expected, rtol=0, atol=1e-9)
    assert run.summary["ends_lower_impact_loss"] == pytest.approx(2.0 * g * height, rel=1e-10)
    rest = run.time > hits[-1]
    assert run["block_position"][rest] == pytest.approx(0.0, abs=1e-15) and (run["block_velocity"][rest] == 0.0).all()
    assert (run["ends_lower_force"][rest] == pytest.approx(2.0 * g, rel=1e-12))
    assert run.summary["energy_relative_residual"] < 1e-10


def test_a_block_slides_to_rest_under_a_stribeck_curve_as_its_quadrature():
    """1 kg launched at 3 m/s against f(v) = 1 + 2 exp(-2 v) + 0.5 v N: m dv / f(v) = -dt, so it stops at
    t = m int_0^3 dv / f(v), int_0^3 m v dv / f(v) from where it started (quadrature to 1e-13), and stays."""
    m, v0 = 1.0, 3.0

    def friction(v):
        return 1.0 + 2.0 * math.exp(-2.0 * v) + 0.5 * v

    stop = quad(lambda v: m / friction(v), 0.0, v0, epsabs=1e-14, epsrel=1e-13)[0]
    distance = quad(lambda v: m * v / friction(v), 0.0, v0, epsabs=1e-14, epsrel=1e-13)[0]
    run = _block(mass=m, velocity=v0, coulomb=1.0, stribeck=2.0, decay=2.0, viscous=0.5, peak=1.001)
    kinds, times = list(run.instants["kind"]), run.instants["time"]
    assert times[kinds.index("lock")] == pytest.approx(stop, abs=1e-10)
    assert run["block_position"][-1] == pytest.approx(distance, abs=1e-10)
    assert run.summary["friction_slip_energy"] == pytest.approx(0.5 * m * v0**2, rel=1e-10)


def test_a_block_pushed_into_its_stop_then_pulled_off_it():
    """A block at its upper stop, pushed into it by 10 N, the push falling 20 N/s from 1 s: the stop holds the push
    (its force the push's opposite, the friction's nothing: the stop takes it first) and lets go at 1.5 s, where the
    push falls through zero; the friction then holds the block until the pull reaches its static force, 1.001 (1 +
    2) N, at 1.65015 s, and the block leaves the stop."""
    run = _block(position=0.5, upper=0.5, force=((0.0, 10.0), (1.0, 10.0), (3.0, -30.0)), coulomb=1.0, stribeck=2.0,
                 decay=2.0, viscous=0.5, peak=1.001)
    kinds, times = list(run.instants["kind"]), run.instants["time"]
    assert times[kinds.index("stop_left")] == pytest.approx(1.5, abs=1e-9)
    assert times[kinds.index("unlock")] == pytest.approx(1.0 + (10.0 + 3.003) / 20.0, abs=1e-9)
    t = run.time
    pushed = t < 1.5
    push = np.where(t < 1.0, 10.0, 10.0 - 20.0 * (t - 1.0))
    np.testing.assert_allclose(run["ends_upper_force"][pushed], -push[pushed], rtol=0, atol=1e-9)
    assert (run["friction_friction"][pushed] == 0.0).all()
    held = (t > 1.5) & (t < 1.65)
    assert (run["block_position"][t < 1.65] == 0.5).all() and (run["ends_upper_contact"][held] == 0).all()
    # what the block passes to the ground through its friction: the pull, held
    np.testing.assert_allclose(run["friction_friction"][held], push[held], rtol=0, atol=1e-9)
    assert run["block_position"][-1] < 0.0 and run.summary["energy_relative_residual"] < 1e-10


def test_a_block_rebounding_between_its_stops_is_where_an_independent_integration_puts_it():
    """1 kg launched at 6 m/s between stops 1 m apart, e = 0.8, against a Stribeck curve (0.5 + 1 exp(-2 |v|) +
    0.2 |v| N): scipy's DOP853 at rtol 1e-12 from stop to stop, the speed reflected at each, to rest; positions within
    1e-8 m, each impact within 1e-9 s, the friction turned round by each rebound."""
    e, peak = 0.8, 1.001

    def friction(v):
        return math.copysign(0.5 + math.exp(-2.0 * abs(v)) + 0.2 * abs(v), v)

    t, s, v, impacts, pieces = 0.0, 0.0, 6.0, [], []
    while True:
        def hit(_, z):
            return (z[0] - 0.5) if v > 0 else (z[0] + 0.5)

        def stopped(_, z):
            return z[1]
        hit.terminal = stopped.terminal = True
        piece = solve_ivp(lambda _, z: [z[1], -friction(z[1])], (t, 10.0), [s, v], method="DOP853", rtol=1e-12,
                          atol=1e-14, events=(hit, stopped), dense_output=True)
        pieces.append(piece)
        t, (s, v) = piece.t[-1], piece.y[:, -1]
        if piece.t_events[1].size:
            break
        impacts.append(t)
        v = -e * v
    run = _block(velocity=6.0, lower=-0.5, upper=0.5, restitution=e, coulomb=0.5, stribeck=1.0, decay=2.0,
                 viscous=0.2, peak=peak)
    kinds, times = np.asarray(run.instants["kind"]), run.instants["time"]
    np.testing.assert_allclose(times[kinds == "stop_rebound"], impacts, rtol=0, atol=1e-9)
    assert (kinds[np.isin(times, times[kinds == "stop_rebound"])] != "lock").all()
    rows = run.time < t
    expected = np.concatenate([p.sol(run.time[rows & (run.time >= p.t[0]) & (run.time < p.t[-1])])[0]
                               for p in pieces])
    np.testing.assert_allclose(run["block_position"][rows][:expected.size], expected, rtol=0, atol=1e-8)
    assert run["block_position"][-1] == pytest.approx(s, abs=1e-8)
    assert run.summary["energy_relative_residual"] < 1e-10


@pytest.mark.parametrize("change, key, says", [
    (part_keys_set("stops", "stop2_ends", {"lower": "0.1 m"}), "drivetrain.stops.stop2_ends.lower",
     "above the start of mass 'stop2'"),
    (part_keys_set("stops", "stop2_ends", {"upper": "-0.5 m"}), "drivetrain.stops.stop2_ends.upper",
     "must be above the lower stop"),
    (part_keys_set("stops", "stop2_ends", {"mass": "nowhere"}), "drivetrain.stops.stop2_ends.mass",
     "no mass 'nowhere'"),
    (part_keys_set("bearing_frictions", "stop2_friction", {"force": None, "torque": "3 N*m"}),
     "drivetrain.bearing_frictions.stop2_friction.torque", "no key of a part on a line"),
    (part_keys_set("bearing_frictions", "stop2_friction", {"viscous": "1 N*m*s/rad"}),
     "drivetrain.bearing_frictions.stop2_friction.viscous", "this one joins masses"),
    (part_keys_set("bearing_frictions", "supportFriction", {"stribeck": "2 N"}),
     "drivetrain.bearing_frictions.supportFriction.stribeck", "a table of the slip speed already"),
])
def test_bad_stops_and_frictions_on_a_line_are_refused_in_one_line(change, key, says, tmp_path):
    refused_in_one_line(FOLDER / "Friction.yaml", change, key, says, tmp_path)


def test_new_values_of_stops_and_stribeck_curves_compile_nothing(runs):
    """A stop's place and restitution, a Stribeck curve's numbers, a table friction's rows: the program Friction
    already compiled."""
    from hoistsim.machine.core import loop

    simulate(load_scenario(FOLDER / "Friction.yaml"))  # its program in hand (a long suite's process may let it go)
    traced = loop.trace_count
    changed = simulate(load_scenario(FOLDER / "Friction.yaml", overrides=[
        "drivetrain.stops.stop2_ends.lower=-0.3 m", "drivetrain.stops.stop2_ends.restitution=0.5",
        "drivetrain.bearing_frictions.stop1_friction.stribeck=4 N",
        "drivetrain.bearing_frictions.stop1_friction.decay=1 s/m",
        "drivetrain.bearing_frictions.stop2_friction.viscous=2 N*s/m"]))
    assert changed["stop2_position"].min() == pytest.approx(-0.3, abs=1e-12)
    assert changed["stop1_position"][-1] != pytest.approx(runs["Friction"]["stop1_position"][-1])
    assert loop.trace_count == traced

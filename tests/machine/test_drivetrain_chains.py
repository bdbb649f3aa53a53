"""Chains of shafts through clutches (``drivetrain:``): properties over random chains, and sweeps over their keys.

- Random chains J1..Jn (n of 2, 3 or 5) with a clutch between each pair of neighbours and a brake on the last
  shaft, forces stepping on and off, a torque in harmonics on J1: at every output row every clutch obeys its
  friction law, a locked clutch does not slip, the heat ledger closes, and without the brake the chain's
  angular momentum is the external torque's integral (in closed form).
- A sweep over a drivetrain key (clutch 2's force in CoupledClutches): each run of the sweep is the run
  simulated alone with that value set.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from helpers import SCENARIOS, property_settings
from hypothesis import example, given
from hypothesis import strategies as st

from hoistsim import load_scenario, scenario_from_dict, simulate, sweep
from hoistsim.references.model import STICK_TOLERANCE
from hoistsim.scenario.sweep_runs import sweep_values

# The same chains every run (a check that passes or fails by the code alone); HOISTSIM_PROPERTY_SEARCH=1
# draws new ones, to search.
SETTINGS = property_settings(40, derandomize=not os.environ.get("HOISTSIM_PROPERTY_SEARCH"))

STUCK, SLIP_FORWARD, SLIP_BACKWARD, OPEN = 0, 1, 2, 3
TINY = 1e-9  # N*m, rad/s: what the switching logic itself resolves (TORQUE_RESOLUTION)
DURATION = 1.0  # s

# Each shaft count is one compiled program (~6 s for two shafts, ~27 s for five), so the counts are few and
# every chain of a count has one structure: every clutch pressed by a table of five rows, the brake always
# drawn (pressed by zeros where the chain has none), the torque on J1 an offset plus two harmonics (zero
# amplitudes where it is a constant).
SHAFT_COUNTS = (2, 3, 5)


def _force_table(times, forces):
    """[[0, F0], [t1, F0], [t1, F1], [t2, F2], [t2, F3]]: held, a step at t1, a ramp, a step at t2."""
    (t1, t2), (f0, f1, f2, f3) = times, forces
    return [["0 s", f"{f0!r} N"], [f"{t1!r} s", f"{f0!r} N"], [f"{t1!r} s", f"{f1!r} N"],
            [f"{t2!r} s", f"{f2!r} N"], [f"{t2!r} s", f"{f3!r} N"]]


def chain(inertias, speeds, clutches, brake, torque):
    """The scene's dict: shafts J1..Jn, clutch<i> between J<i> and J<i+1>, ``brake`` between Jn and ground.

    ``clutches`` and ``brake`` are (static, kinetic share, radius, surfaces, (t1, t2), (F0..F3)), the brake
    None for a chain without one; ``torque`` is (offset, ((amplitude, frequency, phase), ...)).
    """
    n = len(inertias)
    shafts = {f"J{i + 1}": {"inertia": f"{inertias[i]!r} kg*m^2", "speed": f"{speeds[i]!r} rad/s"} for i in range(n)}

    def clutch(between, spec):
        static, share, radius, surfaces, times, forces = spec
        return {"between": between, "static_friction": static, "kinetic_friction": static * share,
                "effective_radius": f"{radius!r} m", "surfaces": surfaces, "force": _force_table(times, forces)}

    drawn = {f"clutch{i + 1}": clutch([f"J{i + 1}", f"J{i + 2}"], spec) for i, spec in enumerate(clutches)}
    drawn["brake"] = clutch([f"J{n}", "ground"], brake or (0.5, 1.0, 0.1, 1, (0.3, 0.6), (0.0, 0.0, 0.0, 0.0)))
    offset, harmonics = torque
    on_j1 = {"offset": f"{offset!r} N*m", "harmonics": [
        {"amplitude": f"{a!r} N*m", "frequency": f"{f!r} Hz", "phase": f"{p!r} rad"} for a, f, p in harmonics]}
    return {"name": "chain", "drivetrain": {"shafts": shafts, "clutches": drawn,
                                            "torques": [{"shaft": "J1", "torque": on_j1}]},
            "simulation": {"duration": f"{DURATION} s", "output_interval": "2 ms", "rtol": 1e-10, "atol": 1e-12}}


_forces = st.one_of(st.just(0.0), st.floats(-30.0, 0.0), st.floats(1.0, 100.0), st.floats(1.0, 100.0))
_step_times = st.tuples(st.floats(0.02, 0.9), st.floats(0.01, 0.5)).map(
    lambda t: (t[0], min(t[0] + t[1], 0.98)))
_clutch_specs = st.tuples(st.floats(0.1, 1.0), st.floats(0.2, 1.0), st.floats(0.05, 1.0), st.integers(1, 3),
                          _step_times, st.tuples(_forces, _forces, _forces, _forces))
_harmonics = st.tuples(st.one_of(st.just(0.0), st.floats(0.5, 40.0)), st.floats(0.1, 5.0),
                       st.floats(0.0, 2 * math.pi))


@st.composite
def chains(draw):
    n = draw(st.sampled_from(SHAFT_COUNTS))
    inertias = draw(st.lists(st.floats(0.1, 5.0), min_size=n, max_size=n))
    speeds = draw(st.lists(st.floats(-20.0, 20.0), min_size=n, max_size=n))
    clutches = draw(st.lists(_clutch_specs, min_size=n - 1, max_size=n - 1))
    brake = draw(st.one_of(st.none(), _clutch_specs))
    torque = draw(st.tuples(st.floats(-20.0, 20.0), st.tuples(_harmonics, _harmonics)))
    return chain(inertias, speeds, clutches, brake, torque)


def _check_friction_law(run, name, spec):
    """One clutch at every row: stuck within its static capacity and not slipping, sliding at its kinetic
    torque against its slip, open (and passing nothing) only where nothing presses it."""
    torque, slip, force, mode = run[f"{name}_torque"], run[f"{name}_slip"], run[f"{name}_force"], run[f"{name}_mode"]
    per_newton = spec.effective_radius * spec.surfaces
    pressing = np.maximum(force, 0.0)  # a force at or below zero presses nothing
    static = spec.static_friction * per_newton * pressing
    kinetic = spec.kinetic_friction * per_newton * pressing
    assert set(np.unique(mode)) <= {STUCK, SLIP_FORWARD, SLIP_BACKWARD, OPEN}, name
    stuck, forward, backward, open_ = (mode == STUCK), (mode == SLIP_FORWARD), (mode == SLIP_BACKWARD), (mode == OPEN)
    over = np.abs(torque[stuck]) - (static[stuck] * (1 + STICK_TOLERANCE) + TINY)
    assert np.all(over <= 0.0), (name, "stuck beyond its capacity", run.time[stuck][np.argmax(over)], over.max())
    np.testing.assert_allclose(torque[forward], kinetic[forward], rtol=1e-12, atol=1e-12, err_msg=f"{name} forward")
    np.testing.assert_allclose(torque[backward], -kinetic[backward], rtol=1e-12, atol=1e-12,
                               err_msg=f"{name} backward")
    assert np.all(slip[forward] >= -TINY) and np.all(slip[backward] <= TINY), (name, "slides against its slip")
    # (the row where a ramp crosses zero is open: the table's value there is zero to round-off)
    round_off = 1e-13 * max(np.abs(force).max(), 1.0)
    assert np.all(torque[open_] == 0.0) and np.all(force[open_] <= round_off), (name, "open while pressed",
                                                                                force[open_].max())
    locked = run[f"{name}_locked"] == 1
    assert np.array_equal(locked, stuck), name
    assert np.all(np.abs(slip[locked]) <= TINY), (name, "slips while locked", np.abs(slip[locked]).max())


def _check_summaries(run, name):
    """The lock-up time is the first locked row's (the lock's own event row is among the rows), NaN if the
    clutch never locks; the heat is the energy series' last value, which never falls."""
    summary = run.summary
    lockup, heat, energy = summary[f"{name}_lockup_time"], summary[f"{name}_slip_energy"], run[f"{name}_energy"]
    locked = np.flatnonzero(run[f"{name}_locked"] == 1)
    if locked.size:
        assert lockup == pytest.approx(run.time[locked[0]], abs=1e-12), name
    else:
        assert math.isnan(lockup), name
    assert heat == pytest.approx(energy[-1], rel=1e-12, abs=1e-12), name
    assert energy[0] == 0.0 and np.all(np.diff(energy) >= -TINY), name


def _torque_impulse(t, offset, harmonics):
    """The integral of offset + sum A sin(2 pi f s + phi) from 0 to t, N*m*s."""
    total = offset * t
    for a, f, p in harmonics:
        w = 2 * math.pi * f
        total = total + a / w * (math.cos(p) - np.cos(w * t + p))
    return total


@pytest.mark.slow
@SETTINGS
@given(chains())
# Two shafts at the same speed: the clutch starts locked and the torque on J1 alone must break it away.
@example(chain([1.0, 2.0], [0.0, 0.0], [(0.5, 0.8, 0.2, 2, (0.2, 0.5), (50.0, 50.0, 10.0, 0.0))], None,
               (3.0, ((15.0, 2.0, 0.0), (0.0, 1.0, 0.0)))))
# Kinetic friction equal to static, the brake sliding against the chain's end turning backwards, a ramp
# down to zero releasing clutch 1.
@example(chain([0.5, 1.0, 2.0], [10.0, -5.0, -8.0],
               [(0.6, 1.0, 0.3, 1, (0.1, 0.4), (0.0, 80.0, -10.0, 40.0)),
                (0.4, 0.5, 0.5, 1, (0.05, 0.7), (20.0, 20.0, 20.0, 0.0))],
               (0.8, 0.75, 0.4, 2, (0.3, 0.6), (100.0, 100.0, -20.0, 60.0)),
               (-5.0, ((10.0, 3.0, 1.0), (5.0, 0.5, 0.0)))))
# Clutch and brake lock, the chain held at rest against 5 + 9 sin(6 pi t) N*m: the brake's margin dips below
# zero within one step (nothing moves, nothing limits the steps); it breaks away where the torque reaches it.
@example(chain([1.0, 1.0], [-1.0, 0.0], [(1.0, 1.0, 1.0, 2, (0.25, 0.5), (0.0, 0.0, 0.0, 7.0))],
               (1.0, 1.0, 1.0, 1, (0.25, 0.5), (0.0, 0.0, 0.0, 13.0)), (5.0, ((0.0, 1.0, 0.0), (9.0, 3.0, 0.0)))))
# A chain at rest but for a speed lost in round-off (the slip resolution is at least that of 1 rad/s): a
# clutch and a brake closing on it, a brake's force ramping down to zero, a torque of one ulp.
@example(chain([1.0, 1.0, 1.0], [0.0, 0.0, 1.9167631456157737e-264],
               [(1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 0.0, 0.0, 0.0)),
                (1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 0.0, 1.0, 0.0))],
               (1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 1.0, 1.0, 0.0)), (0.0, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0)))))
@example(chain([1.0, 1.0, 1.0], [0.0, 0.0, 1.9167631456157737e-264],
               [(1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 0.0, 0.0, 0.0)),
                (1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 0.0, 1.0, 0.0))],
               (1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 0.0, 1.0, 0.0)), (0.0, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0)))))
@example(chain([1.0, 1.0, 1.0], [0.0, 0.0, 1.3523564015188108e-208],
               [(1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 0.0, 0.0, 0.0)),
                (1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 0.0, 0.0, 0.0))],
               (1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 2.0, 0.0, 0.0)),
               (2.220446049250313e-16, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0)))))
def test_every_clutch_of_a_chain_obeys_its_friction_law_at_every_row(data):
    scene = scenario_from_dict(data, name="chain")
    run = simulate(scene)
    for name, spec in scene.drivetrain.clutches.items():
        _check_friction_law(run, name, spec)
        _check_summaries(run, name)
    assert run.energy_balance["relative_residual"] < 1e-8
    # Without a brake the clutches only pass torque between shafts: the chain's angular momentum changes by
    # the torque on J1 alone, whose integral is known in closed form.
    brake = data["drivetrain"]["clutches"]["brake"]["force"]
    if all(float(value.split()[0]) <= 0.0 for _, value in brake):
        shafts = scene.drivetrain.shafts.values()
        momentum = sum(s.inertia * run[f"{name}_speed"] for name, s in scene.drivetrain.shafts.items())
        start = sum(s.inertia * s.speed for s in shafts)
        torque = data["drivetrain"]["torques"][0]["torque"]
        offset = float(torque["offset"].split()[0])
        harmonics = [tuple(float(h[k].split()[0]) for k in ("amplitude", "frequency", "phase"))
                     for h in torque["harmonics"]]
        expected = start + _torque_impulse(run.time, offset, harmonics)
        scale = max(1.0, sum(s.inertia * abs(s.speed) for s in shafts), float(np.max(np.abs(expected))))
        np.testing.assert_allclose(momentum, expected, rtol=0, atol=1e-8 * scale)


# --------------------------------------------------------------------------------------
# a sweep over a drivetrain key

COUPLED = SCENARIOS / "coupled_clutches.yaml"
CLUTCH2_FORCE = "drivetrain.clutches.clutch2.force"
STEP_LEVELS = (10.0, 20.0, 30.0)  # N: clutch 2's step at 0.4 s (the file's is 20 N)


def _stepping_to(level: float) -> str:
    """Clutch 2's force in the file's shape: nothing until 0.4 s, then ``level``."""
    return f"[[0 s, 0 N], [0.4 s, 0 N], [0.4 s, {level:g} N]]"


def _swept_scenario():
    return load_scenario(COUPLED, sweeps=[f"{CLUTCH2_FORCE}=[{', '.join(map(_stepping_to, STEP_LEVELS))}]"])


@pytest.mark.slow
def test_a_shaft_stopping_against_a_clutch_and_a_brake_at_once_is_decided_for_both():
    """Found by the search above (random draws): J3 at -1 and J5 at +1 rad/s, J4 at rest between them, clutches
    3 and 4 slipping (11.5 N*m each), a brake on J5 (2.859375 N*m).  J4 takes as much from J5 as it gives to J3:
    it stays at rest, and J5 stops against clutch 4 and the brake at one instant.  The bisection stops at the
    first of the two roots in list order (clutch 4's); the brake's slip, a few 1e-14 rad/s past zero there
    (the root's resolution in time times J5's deceleration), was once read as still sliding forwards, and the
    brake pulled J4 and J5 backwards for the rest of the run.  Each stage in closed form: J5 stops at
    1/14.359375 s; clutch 4 locks there and the brake turns to slip backwards, J4 and J5 slowing at
    (11.5 - 2.859375)/2 rad/s^2 until J3 (gaining 11.5 rad/s^2) meets them and clutch 3 locks; J3-J5 then come
    to rest against the brake at 2.859375/3 rad/s^2, and the brake locks."""
    kinetic, brake = 0.5 * 46.0 * 0.5, 3.0 * 0.953125
    pulling = (1.0, 0.5, 0.5, 1, (0.5, 0.98), (46.0, 0.0, 0.0, 0.0))
    data = chain([1.0] * 5, [0.0, 0.0, -1.0, 0.0, 1.0],
                 [(1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0,) * 4)] * 2 + [pulling] * 2,
                 (1.0, 1.0, 0.953125, 1, (0.5, 0.98), (3.0, 0.0, 0.0, 0.0)),
                 (0.0, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0))))
    scene = scenario_from_dict(data, name="chain")
    run = simulate(scene)
    for name, spec in scene.drivetrain.clutches.items():
        _check_friction_law(run, name, spec)
    stopped = 1.0 / (kinetic + brake)
    shared = (kinetic - brake) / 2.0
    met = (1.0 + shared * stopped) / (kinetic + shared)
    rest = met + (1.0 - kinetic * met) / (brake / 3.0)
    events = [(round(float(t), 9), e, k) for t, e, k in zip(run.events["time"], run.events["element"],
                                                             run.events["kind"]) if t < 0.5]
    assert [(e, k) for _, e, k in events] == [("clutch4", "lock"), ("brake", "reversal"), ("clutch3", "lock"),
                                              ("brake", "lock")]
    np.testing.assert_allclose([t for t, _, _ in events], [stopped, stopped, met, rest], rtol=0, atol=2e-9)
    assert run.energy_balance["relative_residual"] < 1e-8


def test_a_drivetrain_key_can_be_swept_and_set():
    """The sweep's runs hold clutch 2's table at each level (the rest as in the file), and each is the
    scenario with that table set by an override."""
    runs = list(sweep_values(_swept_scenario()))
    assert len(runs) == len(STEP_LEVELS)
    file = load_scenario(COUPLED).drivetrain
    for level, (label, one) in zip(STEP_LEVELS, runs):
        assert CLUTCH2_FORCE in label
        clutches = one.drivetrain.clutches
        assert clutches["clutch2"].force.times == (0.0, 0.4, 0.4)
        assert clutches["clutch2"].force.values == (0.0, 0.0, level)
        assert clutches["clutch1"] == file.clutches["clutch1"] and clutches["clutch3"] == file.clutches["clutch3"]
        assert one.drivetrain.shafts == file.shafts and one.drivetrain.torques == file.torques
        alone = load_scenario(COUPLED, overrides=[f"{CLUTCH2_FORCE}={_stepping_to(level)}"])
        assert alone.drivetrain == one.drivetrain


@pytest.mark.slow  # three clutches: a compiled program for the sweep's batch and one for a run alone
def test_a_sweep_over_a_drivetrain_key_equals_its_runs_alone():
    result = sweep(_swept_scenario())
    assert len(result.runs) == len(STEP_LEVELS)
    finals = []
    for level, run in zip(STEP_LEVELS, result.runs):
        assert np.all(run["clutch2_force"][run.time > 0.4] == level)
        if level == 20.0:
            continue  # the file's own run: the other two suffice to tell the sweep's values apart
        alone = simulate(load_scenario(COUPLED, overrides=[f"{CLUTCH2_FORCE}={_stepping_to(level)}"]))
        # The batch and the lone run are not the same bits: their switch instants differ by round-off (~1e-12
        # s), and a lock ~1e-12 s apart leaves the speeds ~1e-12 apart after it, times the relative
        # acceleration (a few rad/s^2).  A level the sweep failed to set would move them by whole rad/s.
        assert list(run.events["kind"]) == list(alone.events["kind"])
        np.testing.assert_allclose(run.events["time"], alone.events["time"], rtol=0, atol=1e-11)
        for clutch in ("clutch1", "clutch2", "clutch3"):
            for key in (f"{clutch}_lockup_time", f"{clutch}_slip_energy"):
                assert run.summary[key] == pytest.approx(alone.summary[key], rel=1e-12, nan_ok=True), key
        for shaft in ("J1", "J2", "J3", "J4"):
            assert run[f"{shaft}_speed"][-1] == pytest.approx(alone[f"{shaft}_speed"][-1], rel=1e-11), shaft
        finals.append(run["J4_speed"][-1])
    # a harder clutch 2 locks J2 and J3 sooner: the runs differ, so the sweep did set each level
    assert finals[0] != finals[1]
    lockups = [run.summary["clutch2_lockup_time"] for run in result.runs]
    assert lockups[0] > lockups[1] > lockups[2]


# --------------------------------------------------------------------------------------
# chains with a spring: a spring-damper, or one with backlash, from the second shaft to the third

_springs = st.tuples(st.floats(10.0, 1e4), st.floats(0.1, 20.0), st.floats(-0.5, 0.5))


@st.composite
def sprung_chains(draw, backlash: bool):
    """Three shafts: clutch1 from J1 to J2 (the brake never pressed), a spring from J2 to J3, with a play where
    ``backlash`` (each kind one compiled program)."""
    inertias = draw(st.lists(st.floats(0.1, 5.0), min_size=3, max_size=3))
    speeds = draw(st.lists(st.floats(-20.0, 20.0), min_size=3, max_size=3))
    clutches = [draw(_clutch_specs), (0.5, 1.0, 0.1, 1, (0.3, 0.6), (0.0, 0.0, 0.0, 0.0))]  # clutch2: never pressed
    torque = draw(st.tuples(st.floats(-20.0, 20.0), st.tuples(_harmonics, _harmonics)))
    data = chain(inertias, speeds, clutches, None, torque)
    stiffness, damping, unstretched = draw(_springs)
    spring = {"between": ["J2", "J3"], "stiffness": f"{stiffness!r} N*m/rad", "damping": f"{damping!r} N*m*s/rad",
              "unstretched_angle": f"{unstretched!r} rad"}
    if backlash:
        spring["backlash"] = f"{draw(st.floats(0.0, 0.5))!r} rad"
    data["drivetrain"]["springs"] = {"spring": spring}
    return data


def _sprung_chain_holds(data, ledger=1e-8):
    """Clutch 1 obeys its law at every row, the ledger closes with the spring's energy and its damper's heat
    (within ``ledger``), and the chain's angular momentum changes by the torque on J1 alone (the spring and the
    clutches pass torque between shafts); a backlash's torque never pulls its sides together."""
    scene = scenario_from_dict(data, name="chain")
    run = simulate(scene)
    _check_friction_law(run, "clutch1", scene.drivetrain.clutches["clutch1"])
    assert run.energy_balance["relative_residual"] < ledger
    shafts = scene.drivetrain.shafts
    momentum = sum(s.inertia * run[f"{name}_speed"] for name, s in shafts.items())
    torque = data["drivetrain"]["torques"][0]["torque"]
    harmonics = [tuple(float(h[k].split()[0]) for k in ("amplitude", "frequency", "phase")) for h in torque["harmonics"]]
    expected = sum(s.inertia * s.speed for s in shafts.values()) + _torque_impulse(
        run.time, float(torque["offset"].split()[0]), harmonics)
    scale = max(1.0, sum(s.inertia * abs(s.speed) for s in shafts.values()), float(np.max(np.abs(expected))))
    np.testing.assert_allclose(momentum, expected, rtol=0, atol=1e-8 * scale)
    if "spring_contact" in run.series:
        contact, passed = run["spring_contact"], run["spring_torque"]
        assert np.all(passed * contact >= 0.0) and np.all(passed[contact == 0] == 0.0)
    return run


@pytest.mark.slow
@SETTINGS
@given(sprung_chains(backlash=False))
def test_a_chain_with_a_spring_keeps_its_ledger_and_momentum(data):
    _sprung_chain_holds(data)


@pytest.mark.slow
@pytest.mark.parametrize("speed, unstretched", [(1.0, 0.25), (-2.0, 0.125)])
def test_a_spring_rung_down_between_open_clutches_is_stepped_to_the_end(speed, unstretched):
    """Cases the search found: J2 and J3 rung down on a stiff spring to round-off, every clutch open.  At the
    boundary at 0.6 s two guards at round-off crossed in one step again and again, each pass solved again with
    steps eight times shorter and its crossing found sooner, until the pass that no longer crossed crept on
    at 0.2 us a step and ran out of steps.  A pass is solved again three times at most, and its steps are
    capped only up to the crossing that sent it back."""
    data = chain([1.0, 0.1, 0.1], [speed, 0.0, 0.0],
                 [(1.0, 1.0, 1.0, 1, (0.75, 0.98), (0.0,) * 4), (0.5, 1.0, 0.1, 1, (0.3, 0.6), (0.0,) * 4)],
                 None, (0.0, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0))))
    data["drivetrain"]["springs"] = {"spring": {"between": ["J2", "J3"], "stiffness": "8516.5 N*m/rad",
                                                "damping": "6.1875 N*m*s/rad",
                                                "unstretched_angle": f"{unstretched!r} rad"}}
    run = _sprung_chain_holds(data)
    assert run.time[-1] == DURATION


@pytest.mark.slow
@SETTINGS
@given(sprung_chains(backlash=True))
def test_a_chain_with_backlash_keeps_its_ledger_and_momentum(data):
    # A backlash's ledger holds to the solver's tolerance, a few times looser than a clutch's: on the chain the
    # search found at 2e-8 (rtol 1e-10), its spring alone closes to 2.2e-9, 3.2e-10 and 8.4e-11 at rtol 1e-10,
    # 1e-11 and 1e-12 (the heat of a release, (tau - tau_c) w_rel, integrated through the law's kinks)
    _sprung_chain_holds(data, ledger=1e-7)


def _released_backlash():
    """Found by a random search of the property above: nothing driven, a stiff spring with backlash released
    from a full strain (0.25 rad beyond the play, 74 J), 33 contacts and separations in 1 s."""
    data = chain([1.0, 1.0, 2.0], [0.0, 0.0, 0.0], [(1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0,) * 4),
                                                     (0.5, 1.0, 0.1, 1, (0.3, 0.6), (0.0,) * 4)],
                 None, (0.0, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0))))
    data["drivetrain"]["springs"] = {"spring": {"between": ["J2", "J3"], "stiffness": "9486.0 N*m/rad",
                                                "damping": "4.0 N*m*s/rad", "unstretched_angle": "0.25 rad",
                                                "backlash": "0.25 rad"}}
    return data


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="known: the ledger closes to 2.9e-7 at rtol 1e-10 (7.1e-9 at 1e-11, 2.5e-10 "
                   "at 1e-12): integration error some 3 000 times the rtol, where it accumulates not yet found")
def test_a_backlash_released_from_a_full_strain_closes_its_ledger_to_the_property_s_tolerance():
    _sprung_chain_holds(_released_backlash(), ledger=1e-7)


@pytest.mark.slow
def test_a_chain_whose_steps_fill_their_room_exactly_keeps_its_last_rows():
    """Found by the search above: this chain's run kept exactly as many steps as it had room for (512), and the
    pass's closing write (no crossing, nothing kept) fell on the last place, so the last step's rows, 0.994 to
    0.998 s, read zeros.  A write past a full buffer is now dropped."""
    data = chain([1.5, 1.0, 0.421875], [14.625, -5.36799966219222, -2.1785699153521207],
                 [(0.61328125, 0.2946624755859375 / 0.61328125, 0.48005777533396105, 3,
                   (0.31510638101117927, 0.5539667107931856), (0.0, 81.953125, 0.0, 32.7827421115704)),
                  (0.5, 1.0, 0.1, 1, (0.3, 0.6), (0.0, 0.0, 0.0, 0.0))],
                 None, (-17.020035456084894, ((24.0, 0.849609375, 3.5037287073293704),
                                              (18.60546875, 0.658203125, 5.71875))))
    data["drivetrain"]["springs"] = {"spring": {"between": ["J2", "J3"], "stiffness": "2404.5625 N*m/rad",
                                                "damping": "5.59765625 N*m*s/rad", "unstretched_angle": "0.0 rad",
                                                "backlash": "0.3125 rad"}}
    run = _sprung_chain_holds(data, ledger=1e-7)
    assert run.stats["steps"] - run.stats["rejected_steps"] >= 512
    assert np.all(run["J1_speed"][-5:] > 2.0)


@pytest.mark.slow
def test_a_chain_ringing_down_to_rest_with_open_couplings():
    """Found by the search above: nothing drives it, the spring starts strained by 0.5 rad and rings down (zeta
    0.16 at 38 Hz) to 1e-11 rad/s by 0.74 s.  While the spring's twist was the difference of its shafts' angles
    (0.5 rad, whose round-off is 1e-16 rad), a motion that small no longer moved it: the twist froze, the speeds
    drifted and the stepper failed at 0.857 s for want of steps.  Its twist is now a state of its own."""
    data = chain([1.0, 0.5, 0.109375], [0.0, 0.0, 0.0], [(1.0, 1.0, 1.0, 1, (0.75, 0.98), (0.0, 0.0, 0.0, 0.0)),
                                                         (0.5, 1.0, 0.1, 1, (0.3, 0.6), (0.0, 0.0, 0.0, 0.0))],
                 None, (0.0, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0))))
    data["drivetrain"]["springs"] = {"spring": {"between": ["J2", "J3"], "stiffness": "5142.0 N*m/rad",
                                                "damping": "7.0 N*m*s/rad", "unstretched_angle": "0.5 rad"}}
    _sprung_chain_holds(data)


@pytest.mark.slow
def test_a_chain_with_backlash_closing_a_clutch_on_a_constant_torque():
    """Found by the search above: J1 driven by 1 N*m, clutch 1 closing at 0.5 s (4 N falling to 0 by 0.98 s), a
    backlash (222 N*m/rad, d 1, play 0.03125 rad) from J2 to J3.  The stepper failed for want of steps at
    0.916 s: the sides met where the play's edge was crossed, two guards on one root, the second ending a pass
    1e-15 s after the first and judged overtaken until the steps ran out (the edge crossed outwards is now the
    contact alone).  And the sides' parting at 0.771 s, where J3's speed peaks (the torque on it falls to zero
    there), was lost to that peak's row (an event crossed with the guard located is now recorded)."""
    data = chain([1.0, 1.0, 1.0], [0.0, 0.0, 0.0], [(1.0, 1.0, 1.0, 1, (0.5, 0.98), (0.0, 4.0, 0.0, 0.0)),
                                                     (0.5, 1.0, 0.1, 1, (0.3, 0.6), (0.0, 0.0, 0.0, 0.0))],
                 None, (1.0, ((0.0, 1.0, 0.0), (0.0, 1.0, 0.0))))
    data["drivetrain"]["springs"] = {"spring": {"between": ["J2", "J3"], "stiffness": "222.0 N*m/rad",
                                                "damping": "1.0 N*m*s/rad", "unstretched_angle": "0.0 rad",
                                                "backlash": "0.03125 rad"}}
    run = _sprung_chain_holds(data, ledger=1e-7)
    spring = run.events["element"] == "spring"
    assert list(run.events["kind"][spring]) == ["contact", "separation", "contact"]
    assert run.events["time"][spring][1] == pytest.approx(0.7707211886, abs=1e-8)

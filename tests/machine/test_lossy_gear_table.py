"""A gear stage's loss table (Modelica's LossyGear lossTable) against independent answers and Dymola's trajectories.

The stage alone: an independent scipy integration of Modelica's LossyGear equations as the library writes them
(flange_a.tau, the four quadrants, tau_eta deciding the driving side, startForward / startBackward at rest), with
speed-dependent efficiencies and bearing frictions, the input driving, then the output, then the input again,
the gear stuck and breaking away backwards at its closed-form instant; the coasting of LossyGearDemo3 in closed
form.  MSL 4.0's LossyGearDemo1, 2 and 3 against Dymola's published trajectories (tests/data/modelica/).
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from helpers import SCENARIOS
from modelica_reference import signals
from scipy.integrate import solve_ivp
from scipy.optimize import brentq
from test_modelica_examples import _reference, deviations, mode_changes

from hoistsim import load_scenario, scenario_from_text, simulate
from hoistsim.errors import ScenarioError
from hoistsim.machine.core.element import STICK_TOLERANCE, TORQUE_RESOLUTION

# ----------------------------------------------------------------------------------------- the stage alone
J_IN, J_OUT, RATIO = 0.5, 2.0, 2.0
# [|w_a|, eta_mf1, eta_mf2, tau_bf1, tau_bf2]: three rows, the speed crossing the knot at 1 rad/s
TABLE = np.array([[0.0, 0.7, 0.5, 0.3, 1.2], [1.0, 0.8, 0.55, 0.35, 1.3], [3.0, 0.9, 0.6, 0.4, 1.5]])
# the input driven by 4 N*m for 1 s; the output's load -2 N*m, growing from 2.5 s to -6 N*m at 4 s
INPUT_TORQUE = ([0.0, 1.0, 1.0, 4.0], [4.0, 4.0, 0.0, 0.0])
OUTPUT_TORQUE = ([0.0, 2.5, 4.0], [-2.0, -2.0, -6.0])
SCENE = f"""
name: lossy_gear_table
drivetrain:
  shafts:
    input: {{inertia: {J_IN} kg*m^2, speed: 0 rad/s, angle: 0 deg}}
    output: {{inertia: {J_OUT} kg*m^2, angle: 0 deg}}
  torques:
    - {{shaft: input, torque: [[0 s, 4 N*m], [1 s, 4 N*m], [1 s, 0 N*m]]}}
    - {{shaft: output, torque: [[0 s, -2 N*m], [2.5 s, -2 N*m], [4 s, -6 N*m]]}}
  gears:
    gear: {{between: [input, output], ratio: {RATIO}, loss_table: {TABLE.tolist()}}}
simulation:
  duration: 4 s
  output_interval: 1 ms
  rtol: 1e-12
  atol: 1e-14
"""
# at rest the gear holds the load while tau2 / i stays above -tau_bf2 at rest (the input free: flange_a.tau 0):
# -2 - 4 (t - 2.5) / 1.5 = -2.4 N*m
BREAKAWAY = 2.5 + 0.4 * 1.5 / 4.0


def _torques(t):
    return np.interp(t, *INPUT_TORQUE), np.interp(t, *OUTPUT_TORQUE)


def _table(speed):
    eta1, eta2, bf1, bf2 = (np.interp(abs(speed), TABLE[:, 0], TABLE[:, k]) for k in range(1, 5))
    bf_a = bf1 / 2 if eta1 == eta2 == 1 else (bf1 - bf2) / (eta1 - 1 / eta2)
    return eta1, eta2, bf1, bf2, bf_a


def _rolling(t, w, way):
    """Modelica's LossyGear rolling ``way`` (+1 forwards): (dw_a/dt, tauLoss, tau_eta) from its equations
    0 = flange_b.tau + i (flange_a.tau - tauLoss), J_in a = tau1 - flange_a.tau, J_out a / i = tau2 -
    flange_b.tau, tauLoss by its quadrant: the case whose tau_eta sign is consistent."""
    tau1, tau2 = _torques(t)
    eta1, eta2, bf1, bf2, bf_a = _table(w)
    # tauLoss = k flange_a.tau + way * bf: (input drives, output drives) for this way
    cases = {True: (1 - eta1, bf1), False: (1 - 1 / eta2, bf2)} if way > 0 else \
        {False: (1 - eta1, bf1), True: (1 - 1 / eta2, bf2)}
    for positive, (k, bf) in cases.items():
        a = (tau2 + RATIO * (1 - k) * tau1 - RATIO * way * bf) / (J_OUT / RATIO + RATIO * (1 - k) * J_IN)
        tau_a = tau1 - J_IN * a
        tau_eta = tau_a - way * bf_a
        if (tau_eta >= 0) == positive:
            return a, k * tau_a + way * bf, tau_eta
    raise AssertionError("no consistent quadrant")


def _start(t):
    """+1, -1 or 0: Modelica's startForward / startBackward / stuck for the gear at rest at t (w = 0 values)."""
    tau1, tau2 = _torques(t)
    eta1, eta2, bf1, bf2, bf_a = _table(0.0)
    sa = tau1 + tau2 / RATIO
    most = (1 - eta1) * tau1 + bf1 if tau1 - bf_a > 0 else (1 - 1 / eta2) * tau1 + bf2
    least = (1 - 1 / eta2) * tau1 - bf2 if tau1 + bf_a > 0 else (1 - eta1) * tau1 - bf1
    return 1 if sa > most else -1 if sa < least else 0, sa - most, sa - least


def _scipy_run(t_end=4.0):
    """The stage integrated by scipy (DOP853, rtol 1e-13) from Modelica's equations, piece by piece between the
    torques' knots and the stops: (times, [angle, speed, heat] rows, [(t, kind)] of its locks and unlocks)."""
    knots = [1.0, 2.5, t_end]
    t, y, way = 0.0, np.zeros(3), _start(0.0)[0]
    times, rows, switches = [0.0], [y.copy()], []
    while t < t_end - 1e-12:
        if way == 0:  # stuck: the breakaway, found on a fine grid and by brentq
            grid = np.linspace(t, t_end, 4001)[1:]
            moved = [g for g in grid if _start(g)[0] != 0]
            if not moved:
                break
            way = _start(moved[0])[0]
            t = brentq(lambda s: _start(s)[1 if way > 0 else 2], moved[0] - (grid[1] - grid[0]), moved[0],
                       xtol=1e-15, rtol=1e-15)
            switches.append((t, "unlock"))
            continue

        def field(s, z, way=way):
            a, loss, _ = _rolling(s, z[1], way)
            return [z[1], a, loss * z[1]]

        def stops(s, z):
            return z[1]
        stops.terminal, stops.direction = True, -way
        stop = min(k for k in knots if k > t + 1e-12)
        samples = np.arange(np.floor(t * 1000) + 1, np.ceil(stop * 1000) + 1) / 1000
        sol = solve_ivp(field, (t, stop), y, method="DOP853", rtol=1e-13, atol=1e-15, events=stops,
                        dense_output=True)
        t_next = sol.t_events[0][0] if len(sol.t_events[0]) else stop
        for s in samples[samples <= t_next]:
            times.append(s)
            rows.append(sol.sol(s))
        t, y = t_next, sol.sol(t_next)
        if len(sol.t_events[0]):  # stopped: held, or on the other way
            y[1] = 0.0
            way = _start(t)[0]
            switches.append((t, "lock" if way == 0 else "reversal"))
    # held at rest to the end: the same state at every later grid time
    for s in np.arange(np.floor(times[-1] * 1000) + 1, round(t_end * 1000) + 1) / 1000:
        if way == 0:
            times.append(s)
            rows.append(y.copy())
    return np.asarray(times), np.asarray(rows), switches


@pytest.fixture(scope="module")
def stage_run():
    return simulate(scenario_from_text(SCENE))


@pytest.fixture(scope="module")
def scipy_run():
    return _scipy_run()


def test_the_stage_is_modelicas_lossy_gear_integrated_by_scipy(stage_run, scipy_run):
    """Speed-dependent efficiencies and bearing frictions, the input driving, then the output, then the input
    (its load pulling harder than the decelerating output drives it), at rest, and backwards: hoistsim's stage
    and scipy's integration of Modelica's own equations agree to 1e-10 of the speed and angle's ranges, the heat
    to 1e-10 of its final value (measured: 3e-12); the lock to 1e-9 s, the breakaway at its closed form."""
    run = stage_run
    times, rows, switches = scipy_run
    drives = run["gear_mesh_mode"]
    assert {1, 2, 0} <= set(np.unique(drives).tolist())
    phases = [side for side, _ in itertools.groupby(drives.tolist())]
    assert phases == [1, 2, 1, 0, 2], phases  # in, out, in (its load pulling harder), held, out
    # hoistsim's rows at scipy's grid times (each grid time once in hoistsim: the row after an event there)
    at = np.searchsorted(run.time, times - 1e-12)
    assert np.abs(run.time[at] - times).max() < 1e-12
    for column, k, scale in (("input_angle", 0, np.ptp(rows[:, 0])), ("input_speed", 1, np.ptp(rows[:, 1])),
                             ("gear_mesh_heat", 2, rows[-1, 2])):
        worst = np.abs(run[column][at] - rows[:, k]).max() / scale
        assert worst < 1e-10, (column, worst)
    assert np.allclose(run["output_speed"], run["input_speed"] / RATIO, rtol=1e-14, atol=1e-15)
    ours = [(t, k) for t, k, e in zip(run.events["time"], run.events["kind"], run.events["element"]) if e == "gear"]
    assert [k for _, k in ours] == [k for _, k in switches] == ["lock", "unlock"]
    assert ours[0][0] == pytest.approx(switches[0][0], abs=1e-9)
    # the breakaway: tau2 / i reaches -tau_bf2 at rest (the closed form), hoistsim's later by the core's torque
    # resolution (1e-9 N*m, and 1e-12 of the 1.2 N*m it holds) over the rate its margin falls at, the load's ramp
    # times eta_mf2 at the input
    assert switches[1][0] == pytest.approx(BREAKAWAY, abs=1e-12)
    falling = 4.0 / 1.5 * TABLE[0, 2] / RATIO
    assert ours[1][0] - BREAKAWAY == pytest.approx((TORQUE_RESOLUTION + STICK_TOLERANCE * 1.2) / falling, abs=1e-13)
    assert run.summary["energy_relative_residual"] < 1e-9


def test_the_stage_held_at_rest_holds_its_load_and_loses_nothing(stage_run):
    """Stuck from the stop until the load overcomes the bearings at rest: no speed, no loss power, the tooth load
    the output's load (2 N*m at the output)."""
    run = stage_run
    lock, unlock = run.events["time"][run.events["element"] == "gear"]
    held = (run.time > lock) & (run.time < unlock)
    assert held.sum() > 100
    assert (run["gear_mesh_mode"][held] == 0).all() and (run["input_speed"][held] == 0.0).all()
    assert (run["gear_mesh_loss_power"][held] == 0.0).all()
    load = -np.interp(run.time[held], *OUTPUT_TORQUE)
    np.testing.assert_allclose(run["gear_mesh_torque"][held], load, rtol=1e-13)


@pytest.mark.slow  # a program of its own (~8 s)
def test_coasting_when_no_side_drives_is_the_closed_form():
    """LossyGearDemo3 to its stop: both inertias coasting, the teeth carry nothing (the torque to the output is
    just its half of the bearing friction), the losses 1 N*m whichever side is taken to drive: dw/dt = -1 N*m /
    0.002 kg*m^2 = -500 rad/s^2, stopping at 0.02 s, held through the step of 1 N*m (1.375 N*m would start it)."""
    run = simulate(load_scenario(SCENARIOS / "modelica" / "LossyGearDemo3.yaml"))
    rolling = run.time < 0.02
    np.testing.assert_allclose(run["Inertia1_speed"][rolling], 10.0 - 500.0 * run.time[rolling], rtol=0, atol=1e-12)
    np.testing.assert_allclose(run["Inertia1_angle"][rolling],
                               10.0 * run.time[rolling] - 250.0 * run.time[rolling] ** 2, rtol=0, atol=1e-13)
    np.testing.assert_allclose(run["gear_mesh_torque"][rolling], -0.5, rtol=1e-13)
    (stop,) = run.events["time"][run.events["element"] == "gear"]
    assert stop == pytest.approx(0.02, abs=1e-12)
    assert (run["Inertia1_speed"][run.time > stop] == 0.0).all()
    assert run["gear_mesh_heat"][-1] == pytest.approx(0.5 * 0.002 * 10.0**2, rel=1e-12)
    assert run.summary["energy_relative_residual"] < 1e-9


# ------------------------------------------------------------------------------------ Dymola's trajectories
def _motion_changes(modes: dict, times) -> np.ndarray:
    """The instants the machine starts or stops (every friction element's mode nonzero: it moves)."""
    moving = np.all([m != 0 for m in modes.values()], axis=0)
    return times[1:][np.diff(moving.astype(int)) != 0]


@pytest.mark.slow  # a program of its own for each (8 to 14 s)
@pytest.mark.parametrize("example, moded", [("LossyGearDemo1", ("gear",)),
                                            ("LossyGearDemo2", ("gear", "bearingFriction")),
                                            ("LossyGearDemo3", ("gear",))])
def test_a_lossy_gear_demo_against_dymolas_published_trajectories(example, moded):
    """Inertia2's angle and speed within 1e-3 of their ranges (measured: Demo1 2.7e-6, Demo2 4.1e-6, Demo3
    9.8e-9); the machine starting and stopping where Dymola's modes say it does, within 1e-4 s (measured: 3.3e-8 s);
    every mode change of the gear and the bearing friction at one of hoistsim's switches.

    Dymola starts the gear stuck and leaves that mode at once (its first change, at ~5e-11 s); hoistsim decides
    the mode at t = 0 (rolling, no event).  In LossyGearDemo2 the two frictions hold the same motion at rest,
    and how they share its torque is not determined: Dymola's bearing friction slides with its friction torque at
    the 5e-11 rad/s its tolerance leaves, hoistsim's at zero speed, the gear holding the rest in both; when the
    gear's share reaches its threshold the bearing friction's torque turns (hoistsim's switches at 0.180 s and
    0.456 s: a gear unlock, the bearing friction's reversal and the gear's lock at one instant; Dymola's gear
    rolls at 5e-11 rad/s from 0.456 s instead), and the motion is the same."""
    run = simulate(load_scenario(SCENARIOS / "modelica" / f"{example}.yaml"))
    worst = deviations(run, example, signals(example, run))
    assert max(worst.values()) < 1e-3, worst
    reference = _reference(example)
    late = reference["time"] > 1e-6
    modes = {e: reference[f"{e}.mode"] for e in moded}
    theirs = _motion_changes(modes, reference["time"])
    theirs = theirs[theirs > 1e-6]
    events = run.events
    ours_gear = [(t, k) for t, k, e in zip(events["time"], events["kind"], events["element"]) if e == "gear"]
    # the machine starts or stops where the gear's mode changes, but for a gear that unlocks and locks again
    # at once (within 1e-8 s: the bearing friction's torque turning at rest)
    blips = {i + d for i, ((t, k), (t_next, k_next)) in enumerate(zip(ours_gear, ours_gear[1:]))
             if (k, k_next) == ("unlock", "lock") and t_next - t < 1e-6 for d in (0, 1)}
    ours = np.asarray([t for i, (t, _) in enumerate(ours_gear) if i not in blips])
    assert len(ours) == len(theirs), (ours, theirs)
    np.testing.assert_allclose(ours, theirs, rtol=0, atol=1e-4)
    switches = np.asarray(events["time"])
    for element in moded:
        for t in mode_changes(example, element):
            if t > 1e-6:
                assert np.min(np.abs(switches - t)) < 1e-4, (element, t, switches)
    # from the start the gear rolls the way Dymola's leaves its stuck start for
    first = np.nonzero(late)[0][0]
    assert np.sign(run["Inertia2_speed"][1]) == np.sign(reference["gear.mode"][first]) != 0
    assert run.summary["energy_relative_residual"] < 1e-9


# ---------------------------------------------------------------------------------------------- bad inputs
def _stage(**gear) -> str:
    keys = ", ".join(f"{k}: {v}" for k, v in gear.items())
    return SCENE.replace(f"loss_table: {TABLE.tolist()}", keys)


@pytest.mark.parametrize("gear, key, says", [
    ({"loss_table": "[[0 rad/s, 0.5, 0.5, 0 N*m, 0 N*m], [0 rad/s, 0.6, 0.6, 0 N*m, 0 N*m]]"},
     "drivetrain.gears.gear.loss_table", "row 2: speeds must rise"),
    ({"loss_table": "[[1 rad/s, 0.5, 0.5, 0 N*m, 0 N*m]]"}, "drivetrain.gears.gear.loss_table",
     "the speeds start at 0 rad/s"),
    ({"loss_table": "[[0 rad/s, 0, 0.5, 0 N*m, 0 N*m]]"}, "drivetrain.gears.gear.loss_table", "must be positive"),
    ({"loss_table": "[[0 rad/s, 0.5, 1.2, 0 N*m, 0 N*m]]"}, "drivetrain.gears.gear.loss_table", "at most 1"),
    ({"loss_table": "[[0 rad/s, 0.5, 0.5, -1 N*m, 0 N*m]]"}, "drivetrain.gears.gear.loss_table",
     "must not be negative"),
    ({"loss_table": "[[0 rad/s, 0.5, 0.5, 0 N*m]]"}, "drivetrain.gears.gear.loss_table", "a row of five"),
    ({"loss_table": "[]"}, "drivetrain.gears.gear.loss_table", "must be a table"),
    ({"loss_table": "[[0 rad/s, 1, 1, 1 N*m, 2 N*m]]"}, "drivetrain.gears.gear.loss_table",
     "the two bearing torques must be equal"),
    ({"loss_table": "[[0 rad/s, 0.5, 0.5, 0 N*m, 0 N*m]]", "efficiency": 0.9}, "drivetrain.gears.gear.efficiency",
     "either loss_table or efficiency"),
    ({"loss_table": "[[0 rad/s, 0.5, 0.5, 0 N*m, 0 N*m]]", "backdrive_efficiency": 0.9},
     "drivetrain.gears.gear.backdrive_efficiency", "either loss_table or efficiency"),
], ids=["speeds that do not rise", "not from 0", "efficiency 0", "efficiency above 1", "a negative torque",
        "four columns", "no rows", "an ideal mesh losing more one way", "with an efficiency",
        "with a backdrive efficiency"])
def test_a_bad_loss_table_is_one_line_naming_its_key(gear, key, says):
    with pytest.raises(ScenarioError) as err:
        scenario_from_text(_stage(ratio=RATIO, **gear).replace(f"ratio: {RATIO}, ratio: {RATIO}", f"ratio: {RATIO}"))
    assert err.value.key == key and says in err.value.message and "\n" not in str(err.value), (
        err.value.key, err.value.message)


def test_a_stage_on_a_housing_takes_no_loss_table():
    text = SCENE.replace("    output: {", "    casing: {inertia: 1 kg*m^2}\n    output: {").replace(
        f"ratio: {RATIO}, loss_table", f"ratio: {RATIO}, housing: casing, loss_table")
    with pytest.raises(ScenarioError) as err:
        scenario_from_text(text)
    assert err.value.key == "drivetrain.gears.gear.loss_table" and "give it no loss_table" in err.value.message


def test_a_loss_table_reads_as_modelicas_rows_in_si():
    """Rows in the user's units, converted to SI: a stage with a loss table is lossy, built as LossyGear."""
    text = _stage(loss_table="[[0 rpm, 0.5, 0.4, 0 N*m, 10 N*cm], [60 rpm, 0.9, 0.8, 1 N*m, 2 N*m]]")
    stage = scenario_from_text(text).drivetrain.gears["gear"]
    np.testing.assert_allclose(stage.loss_table, [[0.0, 0.5, 0.4, 0.0, 0.1], [2 * np.pi, 0.9, 0.8, 1.0, 2.0]],
                               rtol=1e-15)
    assert stage.characteristic == "loss_table" and stage.lossy

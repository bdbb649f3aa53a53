"""The elastic rope and the ground against independent answers.

- The exact piecewise solution (hoistsim.references.rope_exact: matrix exponentials, switches as roots of exact
  trajectories): lift-off with the clutch locked, a start with the clutch slipping through lift-off, a
  damped rope, and a snatch from initial slack.
- The textbook pick-up: a drive that keeps its rope speed v lifts the load off at M g / (k v) with a
  peak force M g + v sqrt(k M).
- A damped rope's swings decay by the logarithmic decrement of its damping ratio.
- A very stiff rope is the rigid rope.
- Every run's ledger closes: kinetic + potential + strain energy + every loss.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from helpers import EXERCISE6

from hoistsim import scenario_from_dict, simulate
from hoistsim.references.rope_exact import RopeHoist, solve

STIFFNESS = 2.5e5  # N/m
MASS, G = 500.0, 9.81
PINION_PER_DRUM = 90 / 17


def _scene(force="5000 N", motor="300 rpm", drum=None, rope=None, ground=True, duration="1.5 s", rtol=1e-10,
           **extra):
    data = copy.deepcopy(EXERCISE6)
    data["rope"] = {"stiffness": f"{STIFFNESS} N/m", **(rope or {})}
    if ground:
        data["ground"] = {}
    data["initial"] = {"motor_speed": motor, **({"drum_speed": drum} if drum else {})}
    data["clutch"]["engagement_force"] = force
    data["simulation"].update(duration=duration, output_interval="10 ms", rtol=rtol, atol=rtol * 1e-2)
    data.update(extra)
    return scenario_from_dict(data, name="rope-test")


def _exact(scenario, run):
    hoist = RopeHoist.from_scenario(scenario)
    start = (run["motor_speed"][0], run["drum_speed"][0] * hoist.ratio, run["rope_stretch"][0],
             run["load_velocity"][0])
    return solve(hoist, scenario.simulation.duration, start)


def _switches(run):
    return [(float(t), str(k)) for t, k in zip(run.events["time"], run.events["kind"])]


def _against_exact(scenario, times_within=1e-9, rtol=1e-8):
    run = simulate(scenario)
    exact = _exact(scenario, run)
    got, want = _switches(run), exact.events
    assert [k for _, k in got] == [k for _, k in want]
    np.testing.assert_allclose([t for t, _ in got], [t for t, _ in want], rtol=0, atol=times_within)
    rows = run.grid_rows()
    reference = exact.series(run.time[rows])
    for name, values in reference.items():
        np.testing.assert_allclose(run[name][rows], values, rtol=0,
                                   atol=rtol * np.abs(values).max(), err_msg=name)
    assert run.summary["peak_rope_force"] == pytest.approx(exact.peak_rope_force, rel=rtol)
    assert run.summary["dynamic_factor"] == pytest.approx(exact.peak_rope_force / (MASS * G), rel=rtol)
    # undamped, kinetic + potential + strain energy are conserved; damped, the damper's loss closes it
    assert run.summary["energy_relative_residual"] < 1e-10
    return run, exact


def test_a_start_with_the_clutch_slipping_through_lift_off_is_the_exact_solution():
    run, exact = _against_exact(_scene())
    assert [k for _, k in _switches(run)] == ["lift_off", "lock"]  # lifts while the clutch still slips
    assert run.summary["lift_off_time"] == pytest.approx(exact.events[0][0], abs=1e-9)
    # before lift-off the ground carries what the rope does not
    resting = run["load_on_ground"] == 1
    np.testing.assert_allclose(run["ground_force"][resting] + run["rope_force"][resting], MASS * G, rtol=1e-12)


def test_a_locked_start_lifting_off_and_a_damped_rope_are_the_exact_solution():
    _against_exact(_scene(force="20000 N", motor="0 rpm"))
    _against_exact(_scene(rope={"damping_ratio": 0.05}))


def test_a_snatch_from_initial_slack_is_the_exact_solution():
    """The drum turning at speed takes in 5 cm of slack: the rope snatches taut, the load leaps off the
    ground and the rope goes slack and taut again as it bounces.  Each free flight carries the run's
    speed error into the next switch, so this one runs at rtol 1e-12."""
    scenario = _scene(force="20000 N", drum=f"{300 / PINION_PER_DRUM!r} rpm", rope={"initial_slack": "5 cm"},
                      rtol=1e-12)
    run, _ = _against_exact(scenario)
    kinds = [k for _, k in _switches(run)]
    assert kinds[:2] == ["rope_taut", "lift_off"] and kinds.count("rope_slack") >= 3
    assert run.summary["dynamic_factor"] > 3.0  # a snatch: far above the weight
    slack = run["rope_taut"] == 0
    assert np.all(run["rope_force"][slack] == 0.0) and np.all(run["rope_force"][~slack] > 0.0)


def test_the_textbook_pick_up_by_a_drive_that_keeps_its_rope_speed():
    """An undamped rope, the load resting, the drum turning at v/R with an inertia nothing slows:
    lift-off at t1 = M g / (k v), then F = M g + v sqrt(k M) sin(w (t - t1)), w = sqrt(k / M)."""
    speed = 0.5  # m/s at the rope
    scenario = _scene(force="0 N", motor="0 rpm", drum=f"{speed / 0.2!r} rad/s", duration="0.3 s",
                      flywheel={"shaft": "drum", "inertia": "1e13 kg*m^2"})
    run = simulate(scenario)
    assert run.summary["lift_off_time"] == pytest.approx(MASS * G / (STIFFNESS * speed), rel=1e-8)
    peak = MASS * G + speed * math.sqrt(STIFFNESS * MASS)
    assert run.summary["peak_rope_force"] == pytest.approx(peak, rel=1e-8)
    assert run.summary["dynamic_factor"] == pytest.approx(1 + speed / math.sqrt(G * MASS * G / STIFFNESS), rel=1e-8)
    # (its ledger holds the drum's 3e13 J, whose round-off alone is 1e-2 J: the ledger is checked elsewhere)


def test_a_damped_swing_decays_by_its_logarithmic_decrement():
    """The drum held by its brake, the load dropped 1 mm on a rope of damping ratio 0.05: caught, it swings
    about its static stretch with the rope taut, each rope-force peak exp(-2 pi z / sqrt(1 - z^2)) of the
    one before above the weight, a damped period apart."""
    zeta = 0.05
    scenario = _scene(force="0 N", motor="0 rpm", ground=False, duration="1.2 s",
                      rope={"initial_slack": "1 mm", "damping_ratio": zeta}, brake={"release_time": "10 s"})
    run = simulate(scenario)
    assert [k for _, k in _switches(run)] == ["rope_taut"]  # caught once, never slack again
    rows = run.instants
    peaks = rows["time"][rows["kind"] == "rope_force_peak"]
    force = run["rope_force"][np.searchsorted(run.time, peaks)]
    assert len(peaks) >= 4
    omega = math.sqrt(STIFFNESS / MASS)
    np.testing.assert_allclose(np.diff(peaks), 2 * math.pi / (omega * math.sqrt(1 - zeta**2)), rtol=1e-8)
    np.testing.assert_allclose((force[1:] - MASS * G) / (force[:-1] - MASS * G),
                               math.exp(-2 * math.pi * zeta / math.sqrt(1 - zeta**2)), rtol=1e-7)
    ledger = run.ledger
    assert ledger["rope_damping_loss"][2] > 0
    assert run.summary["energy_relative_residual"] < 1e-9


@pytest.mark.slow  # a rope a million times stiffer: some 10^5 steps
def test_a_very_stiff_rope_is_the_rigid_rope():
    """The brake-start scene (scenarios/engage_at_speed_with_brake.yaml) on a rope of 1e12 N/m."""
    stiff = _scene(force=[["0 s", "0 N"], ["0.5 s", "0 N"], ["0.6 s", "5000 N"]], ground=False,
                   rope={"stiffness": "1e12 N/m", "damping_ratio": 0.2}, duration="2 s",
                   brake={"release_time": "0.6 s"})
    rigid = scenario_from_dict({k: v for k, v in stiff.raw.items() if k != "rope"}, name="rigid")
    elastic, reference = simulate(stiff), simulate(rigid)
    assert reference.summary["lockup_time"] == pytest.approx(1.030, abs=1e-3)
    assert elastic.summary["lockup_time"] == pytest.approx(reference.summary["lockup_time"], abs=1e-6)
    for name in ("motor_speed", "drum_speed", "load_velocity"):
        got = np.interp(reference.time, elastic.time, elastic[name])
        np.testing.assert_allclose(got, reference[name], rtol=0, atol=1e-6 * np.abs(reference[name]).max(),
                                   err_msg=name)


def _wire_rope_scene(free_length="20 m", duration="1.7 s"):
    """The direct start (the clutch pressed hard enough never to slip) on 20 m of steel wire rope,
    E = 100 GPa, 95 mm^2: lifting, the drum winds on about 1 m and the rope stiffens by some 5 %."""
    return _scene(force="20000 N", motor="0 rpm", ground=False, duration=duration,
                  rope={"stiffness": None, "modulus": "100 GPa", "metallic_area": "95 mm^2",
                        "free_length": free_length})


def test_a_wire_rope_stiffening_as_it_winds_on_is_an_independent_integration():
    from scipy.integrate import solve_ivp

    scenario = _wire_rope_scene()
    run = simulate(scenario)
    assert len(run.events["kind"]) == 0  # locked and taut throughout: one smooth phase
    hoist = RopeHoist.from_scenario(scenario.model_copy(update={"rope": scenario.rope.model_copy(
        update={"stiffness": 1.0})}))  # the reduction's inertias and torques; the stiffness is E A / L below
    axial, length = 100e9 * 95e-6, 20.0
    stretch0 = MASS * G * length / axial
    inertia, lever = hoist.motor_inertia + hoist.output_inertia, hoist.lever

    def field(t, z):
        speed, stretch, load_speed, height = z
        k = axial / (length - (stretch - stretch0 + height))
        force = k * stretch
        torque = hoist.stall_torque * (1 - speed / hoist.no_load_speed)
        return [(torque - lever * force) / inertia, lever * speed - load_speed, force / MASS - G, load_speed]

    grid = run.time[run.grid_rows()]
    reference = solve_ivp(field, (0.0, grid[-1]), [0.0, stretch0, 0.0, 0.0], method="DOP853", t_eval=grid,
                          rtol=1e-12, atol=1e-14)
    speed, stretch, load_speed, height = reference.y
    wound = stretch - stretch0 + height
    assert 0.9 < wound[-1] < 1.2  # about 1 m of the 20 wound on: k up by about 5 %
    force = axial / (length - wound) * stretch
    expected = {"drum_speed": speed / hoist.ratio, "rope_stretch": stretch, "load_velocity": load_speed,
                "load_position": height, "rope_force": force, "rope_stiffness": axial / (length - wound)}
    for name, values in expected.items():
        np.testing.assert_allclose(run[name][run.grid_rows()], values, rtol=0, atol=1e-8 * np.abs(values).max(),
                                   err_msg=name)
    assert run.summary["energy_relative_residual"] < 1e-10  # with the stiffening's work in the ledger
    assert run.ledger["rope_stiffening"][2] > 0


def test_a_rope_too_short_for_what_the_drum_winds_on_is_a_scenario_error():
    """One line naming rope.free_length and the instant it is all wound on: a run that stops just before
    that instant has wound on just under the free length."""
    import re

    from hoistsim import ScenarioError

    with pytest.raises(ScenarioError, match=r"rope\.free_length: is too short: the drum has wound all of it on "
                                            r"at t = [\d.]+ s") as raised:
        simulate(_wire_rope_scene(free_length="0.4 m", duration="1.7 s"))
    assert "\n" not in str(raised.value)
    instant = float(re.search(r"t = ([\d.]+) s", str(raised.value)).group(1))
    short = simulate(_wire_rope_scene(free_length="0.4 m", duration=f"{instant * 0.999} s"))
    stretch0 = MASS * G * 0.4 / (100e9 * 95e-6)
    wound = short["rope_stretch"][-1] - stretch0 + short["load_position"][-1]
    assert 0.4 * 0.99 < wound < 0.4


@pytest.mark.slow
def test_a_sweep_over_the_rope_is_one_compiled_program_and_each_run_is_its_single_run():
    """Stiffness, damping and slack are traced numbers: a sweep over all three compiles one program, a
    sweep over other values of them none, and each run's peak and lift-off are those of the run alone."""
    from hoistsim import sweep
    from hoistsim.machine.core import loop
    from hoistsim.scenario.sweep_runs import sweep_values

    def swept(stiffness, damping, slack):
        scenario = _scene(duration="0.8 s")
        data = {**scenario.raw, "sweep": {"rope.stiffness": stiffness, "rope.damping_ratio": damping,
                                          "rope.initial_slack": slack}}
        return scenario_from_dict(data, name="rope-sweep")

    first = swept(["2e5 N/m", "4e5 N/m"], [0.0, 0.05], ["0 m", "2 cm"])
    result = sweep(first, summary_only=True)
    before = loop.trace_count
    sweep(swept(["3e5 N/m", "6e5 N/m"], [0.1, 0.02], ["1 cm", "0 m"]), summary_only=True)
    assert loop.trace_count == before
    assert len(result) == 8
    for (label, one), peak, lift_off in zip(sweep_values(first), result.summary["peak_rope_force"],
                                            result.summary["lift_off_time"]):
        alone = simulate(one).summary
        assert peak == pytest.approx(alone["peak_rope_force"], rel=1e-9), label
        assert lift_off == pytest.approx(alone["lift_off_time"], abs=1e-9), label
    # every key changes the answer (a slipping clutch pulls with a constant force: without slack, the
    # peak force of a linear rope under a constant pull does not depend on its stiffness; lift-off does)
    told = zip(np.round(result.summary["peak_rope_force"], 3), np.round(result.summary["lift_off_time"], 6))
    assert len(set(told)) == 8


@pytest.mark.parametrize("summary_only", [True, pytest.param(False, marks=pytest.mark.slow)])
def test_a_sweep_run_that_winds_its_rope_on_entirely_fails_the_sweep_naming_the_run(summary_only):
    from hoistsim import ScenarioError, sweep

    scenario = _wire_rope_scene(free_length="20 m", duration="1.2 s")
    data = {**scenario.raw, "sweep": {"rope.free_length": ["20 m", "0.4 m"]}}
    with pytest.raises(ScenarioError, match=r"rope\.free_length: is too short: the drum has wound all of it on "
                                            r"at t = [\d.]+ s .*\(run rope\.free_length=0\.4 m\)$"):
        sweep(scenario_from_dict(data, name="short-rope-sweep"), summary_only=summary_only)


def test_the_command_line_refuses_that_sweep_in_one_line_and_writes_nothing(tmp_path):
    from click.testing import CliRunner
    from ruamel.yaml import YAML

    from hoistsim.cli import main

    scenario = _wire_rope_scene(free_length="20 m", duration="1.2 s")
    path = tmp_path / "short.yaml"
    YAML(typ="safe").dump({**scenario.raw, "sweep": {"rope.free_length": ["20 m", "0.4 m"]}}, path)
    out = tmp_path / "short.h5"
    result = CliRunner().invoke(main, ["run", str(path), "-o", str(out)])
    assert result.exit_code == 2, result.output
    errors = [line for line in result.stderr.splitlines() if line.startswith("hoistsim: error: ")]
    assert len(errors) == 1 and "rope.free_length: is too short" in errors[0] and "Traceback" not in result.output
    assert list(tmp_path.iterdir()) == [path]


def _rigid_on_the_ground(open_at="1.0 s"):
    """The engage-at-speed scene with the load resting on the ground instead of a brake holding it: the
    clutch's force ramps to 5 kN over 0.5-0.6 s, and the clutch opens again at ``open_at``."""
    data = copy.deepcopy(EXERCISE6)
    data["ground"] = {}
    data["initial"] = {"motor_speed": "300 rpm"}
    data["clutch"]["engagement_force"] = [["0 s", "0 N"], ["0.5 s", "0 N"], ["0.6 s", "5000 N"],
                                          [open_at, "5000 N"], [open_at, "0 N"]]
    data["simulation"].update(duration="3 s", output_interval="10 ms")
    return scenario_from_dict(data, name="rigid-ground")


def test_a_load_on_a_rigid_rope_rests_until_the_clutch_lifts_it_and_lands_in_a_plastic_impact():
    """Slipping, the clutch passes f c F(t); the load lifts off where that reaches M g R / tau (the ramp's
    closed form).  Opened at 1 s, the drum side coasts up, decelerating at T_L / J_b, and comes down:
    it lands where the height returns to zero, and the landing takes the drum side's kinetic energy."""
    from hoistsim.references.model import Machine

    scenario = _rigid_on_the_ground()
    run = simulate(scenario)
    d = Machine.from_scenario(scenario).reduced()
    sliding_per_newton = d.kinetic_friction * d.clutch_constant
    lift_off = 0.5 + 0.1 * (d.load_torque / sliding_per_newton) / 5000.0
    assert run.summary["lift_off_time"] == pytest.approx(lift_off, abs=1e-9)
    ground = run.events["element"] == "ground"
    assert list(run.events["kind"][ground]) == ["lift_off", "touch_down"]
    # after the clutch opens (t_o), the height is a parabola: x_o + v_o u - a u^2 / 2, a = R T_L / (tau J_b)
    opened = np.searchsorted(run.time, 1.0)
    x0, v0 = run["load_position"][opened], run["load_velocity"][opened]
    decel = d.rope_radius * d.load_torque / (d.ratio * d.output_inertia)
    landing = 1.0 + (v0 + math.sqrt(v0**2 + 2 * decel * x0)) / decel
    touch_down = run.events["time"][run.events["kind"] == "touch_down"][0]
    assert touch_down == pytest.approx(landing, abs=1e-8)
    speed_then = v0 - decel * (touch_down - 1.0)  # m/s at the rope
    pinion = speed_then / d.rope_radius * d.ratio
    assert run.summary["landing_loss"] == pytest.approx(0.5 * d.output_inertia * pinion**2, rel=1e-8)
    after = run.time > touch_down
    assert np.all(run["load_position"][after] == run["load_position"][after][0])
    assert abs(run["load_position"][after][0]) < 1e-9 and np.all(run["drum_speed"][after] == 0.0)
    assert np.all(run["load_on_ground"][after] == 1)
    assert run.summary["energy_relative_residual"] < 1e-9  # the landing's loss closes the ledger


def test_the_shipped_lift_off_scene_says_what_its_header_says():
    from helpers import SCENARIOS

    from hoistsim import load_scenario

    run = simulate(load_scenario(SCENARIOS / "lift_off_the_ground.yaml"))
    s = run.summary
    assert s["lift_off_time"] == pytest.approx(0.058, abs=5e-4)
    assert s["lockup_time"] == pytest.approx(0.350, abs=5e-4)
    assert s["peak_rope_force"] == pytest.approx(9210, abs=5)
    assert s["dynamic_factor"] == pytest.approx(1.88, abs=5e-3)
    assert s["dynamic_factor_standard"] == pytest.approx(1.10 + 0.34 * 0.2 * np.interp(
        s["lift_off_time"], run.time, run["drum_speed"]), rel=1e-6)
    # the bearings feel the rope: the rope tension column is the rope's force
    np.testing.assert_allclose(run["rope_tension"], run["rope_force"], rtol=1e-12, atol=1e-9)
    assert s["energy_relative_residual"] < 1e-8
    # the teeth pass what the pinion side passes (here massless: the clutch's torque, geared up) and the drum
    # shaft takes it: its inertia's share and the rope's pull on its radius (the drum's momentum balance)
    wheel_radius, drum_radius, drum_inertia = 0.5 * 4e-3 * 90, 0.2, 40.0
    teeth = run["tooth_tangential_force"] * wheel_radius
    np.testing.assert_allclose(teeth, run["clutch_torque"] * PINION_PER_DRUM, rtol=0, atol=1e-9 * teeth.max())
    inner = (run.time > 0.01) & (np.abs(run.time - s["lockup_time"]) > 0.01) & (np.abs(run.time - s["lift_off_time"])
                                                                                 > 0.01)
    drum_acceleration = np.gradient(run["drum_speed"], run.time)
    taken = drum_inertia * drum_acceleration + run["rope_force"] * drum_radius
    np.testing.assert_allclose(teeth[inner], taken[inner], rtol=0, atol=1e-3 * teeth.max())

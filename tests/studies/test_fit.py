"""Friction fitted to a trace: synthetic traces from known values with seeded noise fitted back within the
reported 95 % intervals, from a start 50 % off that puts the lock and the breakaway rows away, and from a
start where the trace cannot see a key (the sweep of starting points finds it); a key the trace never sees
and residuals that are not the noise said to be so; the fitted file changed only on its fitted keys' lines;
the table within 80 columns; bad input refused at one line."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SCENARIOS

from hoistsim import load_scenario, simulate
from hoistsim.cli import main
from hoistsim.studies.fit import fit
from hoistsim.studies.fit_checks import residual_check, undetermined
from hoistsim.studies.measured_trace import Trace

RIG = SCENARIOS / "clutch_rig.yaml"
TRACE = SCENARIOS / "clutch_rig_trace.csv"
TRUE = {"clutch.static_friction": 0.33, "clutch.kinetic_friction": 0.09}
START = {key: 1.5 * value for key, value in TRUE.items()}  # 50 % off
KEYS = list(TRUE)
MATCH = ["motor_speed", "drum_speed"]
NOISE = {"motor_speed": 0.1, "drum_speed": 0.02}  # rad/s: about 1 and 0.2 rpm


def _setting(values: dict) -> list[str]:
    return [f"{key}={value!r}" for key, value in values.items()]


@pytest.fixture(scope="module")
def true_run():
    """The rig's run at the true friction, every 10 ms (its grid rows: no event rows)."""
    run = simulate(load_scenario(RIG, overrides=_setting(TRUE) + ["simulation.output_interval=10 ms"]))
    rows = run.grid_rows()
    return run.time[rows], {name: run.series[name][rows] for name in MATCH}


def _trace(true_run, seed: int) -> Trace:
    time, exact = true_run
    rng = np.random.default_rng(seed)
    columns = {name: exact[name] + rng.normal(0.0, NOISE[name], time.size) for name in MATCH}
    return Trace(f"seed {seed}", time, columns, {name: "rad/s" for name in MATCH}, {name: "rad/s" for name in MATCH})


def _lock_and_breakaway(values: dict) -> list[float]:
    run = simulate(load_scenario(RIG, overrides=_setting(values)))
    return [t for t, kind in zip(run.events["time"], run.events["kind"]) if kind in ("lock", "unlock")]


def test_a_fit_from_far_off_moves_the_switches_back_onto_the_measured_rows(true_run):
    # from the start itself (no sweep of starting points): Levenberg-Marquardt moves the switches
    result = fit(load_scenario(RIG, overrides=_setting(START)), _trace(true_run, 1), MATCH, KEYS, starts=0)
    assert result.sound, result.warnings
    for key in KEYS:
        low, high = result.intervals[key]
        assert low < TRUE[key] < high, (key, result.values[key], result.intervals[key])
    # the start's lock and breakaway are five measured rows (10 ms apart) or more from the trace's
    moved = np.abs(np.subtract(_lock_and_breakaway(START), _lock_and_breakaway(TRUE)))
    assert moved.size == 2 and np.all(moved > 0.05), moved
    assert np.abs(np.subtract(_lock_and_breakaway(result.values), _lock_and_breakaway(TRUE))).max() < 0.01
    # the residuals are the noise: their RMS is its standard deviation, to sampling
    for name in MATCH:
        assert result.residual_rms[name] == pytest.approx(NOISE[name], rel=0.15)


@pytest.mark.slow
def test_the_95_percent_intervals_hold_the_true_values_as_often_as_they_say(true_run):
    """Twelve seeded traces, two keys each: 24 intervals, 22.8 expected to hold the true value; these seeds
    give 23 (a fixed set: the count is exact, and 21 or fewer would say the intervals are too narrow)."""
    held = 0
    for seed in range(100, 112):
        result = fit(load_scenario(RIG, overrides=_setting(START)), _trace(true_run, seed), MATCH, KEYS, starts=0)
        assert result.converged, seed
        held += sum(result.intervals[key][0] < TRUE[key] < result.intervals[key][1] for key in KEYS)
    assert held >= 22


def _fit_cli(tmp_path, *options, trace=TRACE, env=None):
    output = tmp_path / "fitted.yaml"
    done = CliRunner().invoke(main, ["fit", str(RIG), "--measured", str(trace), "--match", ",".join(MATCH),
                                     "--fit", ",".join(KEYS), "-o", str(output), *options], env=env)
    return done, output


def _widest(printed: str) -> int:
    """The widest line a fit prints, its "wrote FILE" line (the paths as given) left out."""
    return max(len(line) for line in printed.splitlines() if not line.startswith("wrote "))


def _changed_lines(original: str, written: str) -> dict[int, str]:
    """The written file's lines that differ from the original's, by index (the files have as many lines)."""
    before, after = original.splitlines(keepends=True), written.splitlines(keepends=True)
    assert len(before) == len(after), (before, after)
    return {k: line for k, (old, line) in enumerate(zip(before, after)) if old != line}


def test_the_command_writes_the_fitted_scenario_and_its_figure(tmp_path):
    figure = tmp_path / "fit.png"
    done, output = _fit_cli(tmp_path, "--plot", str(figure), env={"COLUMNS": "80"})
    assert done.exit_code == 0, done.output
    assert "95 % low" in done.stdout and "residual RMS" in done.stdout and "converged in" in done.stdout
    assert _widest(done.stdout) <= 80, done.stdout
    assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    fitted = load_scenario(output, strict=True)
    assert fitted.clutch.static_friction == pytest.approx(TRUE["clutch.static_friction"], abs=0.002)
    assert fitted.clutch.kinetic_friction == pytest.approx(TRUE["clutch.kinetic_friction"], abs=0.0005)
    # every line as it was but the fitted keys', each of those naming the trace, the RMS and its interval
    changed = _changed_lines(RIG.read_text(), output.read_text())
    assert sorted(line.split(":")[0].strip() for line in changed.values()) == ["kinetic_friction", "static_friction"]
    for line in changed.values():
        assert f"# fitted to {TRACE} (RMS motor_speed 1.03 rpm, drum_speed 0.197 rpm): 95 % interval 0." in line
    import json

    printed = json.loads(CliRunner().invoke(main, ["fit", str(RIG), "--measured", str(TRACE), "--match",
                                                   ",".join(MATCH), "--fit", ",".join(KEYS), "--json"]).stdout)
    assert set(printed) == {*KEYS, "rms", "residuals", "warnings"} and printed["warnings"] == []
    assert set(printed[KEYS[0]]) == {"value", "standard_error", "interval_95", "determined"}
    assert printed[KEYS[0]]["value"] == pytest.approx(fitted.clutch.static_friction, rel=1e-5)


# The case: a hoist whose clutch locks at 0.70 s (0.12 kinetic friction, 200 kg), its motor's speed
# measured with 0.05 rad/s of noise, fitted from a load so heavy (800 kg, 0.09) that the clutch never locks:
# there the motor's speed does not depend on the load's mass at all.
HOIST_TRUE = {"clutch.kinetic_friction": 0.12, "load.mass": 200.0}
HOIST_START = {"clutch.kinetic_friction": 0.09, "load.mass": 800.0}
HOIST_RANGES = {"clutch.kinetic_friction": (0.05, 0.2), "load.mass": (50.0, 2000.0)}
HOIST_NOISE = 0.05


@pytest.fixture(scope="module")
def hoist_trace():
    run = simulate(load_scenario(RIG, overrides=_setting(HOIST_TRUE) + ["simulation.output_interval=10 ms"]))
    locks = [t for t, kind in zip(run.events["time"], run.events["kind"]) if kind == "lock"]
    assert locks == [pytest.approx(0.697, abs=0.005)]
    rows = run.grid_rows()
    time = run.time[rows]
    noisy = run.series["motor_speed"][rows] + np.random.default_rng(51).normal(0.0, HOIST_NOISE, time.size)
    return Trace("hoist.csv", time, {"motor_speed": noisy}, {"motor_speed": "rad/s"}, {"motor_speed": "rad/s"})


def _never_locks(values: dict) -> bool:
    return "lock" not in list(simulate(load_scenario(RIG, overrides=_setting(values))).events["kind"])


def test_a_key_the_start_hides_is_undetermined_there_and_found_by_the_sweep(hoist_trace):
    assert _never_locks(HOIST_START)
    keys = list(HOIST_TRUE)
    # from the start alone: the mass cannot move, has no interval, and the fit says it does not explain the trace
    stuck = fit(load_scenario(RIG, overrides=_setting(HOIST_START)), hoist_trace, ["motor_speed"], keys, starts=0)
    assert "column of the Jacobian is zero" in stuck.undetermined["load.mass"]
    assert stuck.intervals["load.mass"] is None and stuck.standard_errors["load.mass"] is None
    assert stuck.values["load.mass"] == HOIST_START["load.mass"]
    assert not stuck.sound and stuck.checks["motor_speed"].far_from_noise and stuck.checks["motor_speed"].patterned
    assert any(w.startswith("load.mass: the trace does not depend on it here") for w in stuck.warnings)
    assert any(w.startswith("motor_speed: the residual RMS") and "times the noise" in w for w in stuck.warnings)
    # the keys' ranges swept first: the truth within the intervals, the residuals the noise
    found = fit(load_scenario(RIG, overrides=_setting(HOIST_START)), hoist_trace, ["motor_speed"], keys,
                ranges=HOIST_RANGES)
    assert found.swept.moved and found.sound, found.warnings
    for key in keys:
        low, high = found.intervals[key]
        assert low < HOIST_TRUE[key] < high, (key, found.values[key], found.intervals[key])
    assert found.residual_rms["motor_speed"] == pytest.approx(HOIST_NOISE, rel=0.15)
    assert found.checks["motor_speed"].noise == pytest.approx(HOIST_NOISE, rel=0.15)


def test_a_key_the_trace_never_sees_is_undetermined_and_kept_at_its_value(hoist_trace):
    """The gears' module sets the wheels' size, not their ratio: no speed depends on it, anywhere."""
    keys = ["clutch.kinetic_friction", "gears.module"]
    result = fit(load_scenario(RIG, overrides=_setting({"load.mass": 200.0})), hoist_trace, ["motor_speed"], keys,
                 ranges={"clutch.kinetic_friction": (0.05, 0.2)})
    assert list(result.undetermined) == ["gears.module"]
    assert result.values["gears.module"] == pytest.approx(0.004)  # swept, then given back: nothing says where
    assert result.to_dict()["gears.module"]["interval_95"] is None
    low, high = result.intervals["clutch.kinetic_friction"]
    assert low < HOIST_TRUE["clutch.kinetic_friction"] < high
    assert result.warnings == ["gears.module: the trace does not depend on it here (its column of the Jacobian is "
                               "zero): undetermined"]


def test_the_command_says_what_the_trace_does_not_determine(tmp_path, hoist_trace, monkeypatch):
    monkeypatch.chdir(tmp_path)  # the trace named as a user names it beside them (a long path is one word of a line)
    trace = Path("hoist.csv")
    trace.write_text("time [s],motor_speed [rad/s]\n" + "".join(
        f"{t:.2f},{v:.6f}\n" for t, v in zip(hoist_trace.time, hoist_trace.columns["motor_speed"])))
    output = tmp_path / "fitted.yaml"
    done = CliRunner().invoke(main, ["fit", str(RIG), "--measured", str(trace), "--match", "motor_speed",
                                     "--fit", ",".join(HOIST_TRUE), "--starts", "0", "-o", str(output),
                                     *(f"--set={setting}" for setting in _setting(HOIST_START))],
                              env={"COLUMNS": "80"})
    assert done.exit_code == 0, done.output
    assert _widest(done.stdout) <= 80, done.stdout
    assert "converged" not in done.stdout and "not a sound fit" in done.stdout and "undetermined" in done.stdout
    warned = [line for line in done.stderr.splitlines() if line.startswith("hoistsim: warning: ")]
    assert any("load.mass: the trace does not depend on it here" in line for line in warned), done.stderr
    changed = _changed_lines(RIG.read_text(), output.read_text())  # the --set of fitted keys not noted
    mass = [line for line in changed.values() if line.strip().startswith("mass:")]
    assert mass == [f"  mass: 500 kg  # not determined by {trace}: left as it was\n"]


def test_residuals_that_are_noise_pass_and_a_pattern_does_not():
    rng = np.random.default_rng(3)
    noise = rng.normal(0.0, 0.05, 300)
    clean = residual_check(noise)
    assert clean.noise == pytest.approx(0.05, rel=0.15) and not clean.far_from_noise and not clean.patterned
    drift = residual_check(noise + 0.5 * np.sin(np.linspace(0.0, 6.0, 300)))
    assert drift.noise == pytest.approx(0.05, rel=0.2) and drift.far_from_noise and drift.patterned


def test_keys_seen_only_as_a_product_are_undetermined():
    """A slipping clutch's torque is its force times its friction: columns proportional, JᵀJ singular."""
    rng = np.random.default_rng(4)
    slip = rng.normal(size=(200, 1))
    force, friction, inertia = 5000.0, 0.1, 0.9
    jacobian = np.hstack([slip / force, slip / friction, rng.normal(size=(200, 1)) / inertia])
    reasons = undetermined(jacobian, np.array([force, friction, inertia]), ["force", "friction", "inertia"])
    assert set(reasons) == {"force", "friction"} and "combination with friction" in reasons["force"]
    jacobian[:, 1] += 1e-3 * rng.normal(size=200) / friction  # told apart, if barely: determined
    assert undetermined(jacobian, np.array([force, friction, inertia]), ["force", "friction", "inertia"]) == {}


def _csv(tmp_path, text: str):
    path = tmp_path / "trace.csv"
    path.write_text(text)
    return path


@pytest.mark.parametrize("text, options, message", [
    ("time [s],motor_speed [rpm]\n0,1\n0.1,2\n", [], "has no column 'drum_speed'"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n0.2,2,2\n0.1,3,3\n", [], "the times must increase"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n0.1,nan,2\n", [], "'nan' is not a finite number"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n0.1,x,2\n", [], "'x' is not a number"),
    ("time [s],motor_speed [blorp],drum_speed [rpm]\n0,1,1\n0.1,2,2\n", [], "not a unit hoistsim knows"),
    ("time [s],motor_speed [N],drum_speed [rpm]\n0,1,1\n0.1,2,2\n", [], "not a unit of the series' kind"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n5,2,2\n", [], "outside the run's"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n0.1,2,2\n0.2,3,3\n",
     ["--bounds", "clutch.kinetic_friction=0.2"], "expected KEY=LO:HI"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n0.1,2,2\n0.2,3,3\n",
     ["--range", "clutch.static_friction=0.2:0.4,clutch.kinetic_friction=0.2"], "--range: expected KEY=LO:HI"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n0.1,2,2\n0.2,3,3\n",
     ["--range", "load.mass=100 kg:2 t"], "--range load.mass: is not a fitted key"),
    ("time [s],motor_speed [rpm],drum_speed [rpm]\n0,1,1\n0.1,2,2\n0.2,3,3\n",
     ["--range", "clutch.kinetic_friction=0.2:0.1"], "--range clutch.kinetic_friction: the low end 0.2 is not below"),
])
def test_a_bad_trace_or_option_ends_at_one_line_and_writes_nothing(tmp_path, text, options, message):
    done, output = _fit_cli(tmp_path, *options, trace=_csv(tmp_path, text))
    assert done.exit_code == 2, done.output
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error: ") and message in lines[0], lines
    assert not output.exists()


def test_a_key_that_is_not_a_number_is_refused(tmp_path):
    done = CliRunner().invoke(main, ["fit", str(RIG), "--measured", str(TRACE), "--match", "motor_speed",
                                     "--fit", "clutch", "-o", str(tmp_path / "f.yaml")])
    assert done.exit_code == 2 and "--fit: clutch: is a section" in done.stderr, done.stderr

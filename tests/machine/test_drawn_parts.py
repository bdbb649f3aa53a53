"""The parts a drawn drivetrain shares with the hoist (brakes, ratchets, rotors, slider-cranks, ripples, a clutch's
heating, the load's rope, ground and bearings), against independent answers, and the hoist as the drivetrain its
template writes out.

- The hoist is the drivetrain ``hoistsim check --drivetrain`` prints: that scenario, run, gives every column and
  summary of the hoist's under the drawn names, to round-off (bit for bit where the sums are the same); a
  machine with a periodic regime has its rows of each period besides, so its steps differ: to the solver's
  tolerance on the grid.
- A brake on any shaft: the closed-form stop, its heat the kinetic energy.  A pawl: holds a torque one way.
- A clutch's heating with no cooling: its temperature rises by its slip energy over its heat capacity.
- A slider-crank and a resisting ripple on a free shaft: the angle-domain energy theorem.
- Bad input: one line naming the key.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SCENARIOS

from hoistsim import _jax, load_scenario, scenario_from_dict, scenario_from_text, simulate
from hoistsim.cli import main
from hoistsim.errors import ScenarioError
from hoistsim.machine.core import loop
from hoistsim.studies.hoist_drawing import hoist_as_drivetrain

TIGHT = {"rtol": 1e-10, "atol": 1e-12}


def _drawn(duration="2 s", **parts):
    return scenario_from_dict({"name": "drawn", "drivetrain": parts,
                               "simulation": {"duration": duration, "output_interval": "10 ms", **TIGHT}}, name="drawn")


def _same_run(hoist, drawn, renamed, rel, tighter=None):
    """Every column and summary value of the hoist's run in the drawn one's, under its drawn name: within ``rel``
    of its scale; or, given the hoist solved far ``tighter``, on the grid within twice the hoist's own error
    against that (and 1e-12 of its scale).  (The hoist's periodic rows end passes the drawing runs on through:
    their steps differ, and so do the runs, by less than either is from the answer.)"""
    rows = (hoist.grid_rows(), drawn.grid_rows(), tighter.grid_rows()) if tighter else (slice(None),) * 3
    if tighter is None:
        assert len(hoist.time) == len(drawn.time)
    for name, column in hoist.series.items():
        if name == "kinetic_energy":  # the periodic regime's (no drawn key)
            continue
        mine = np.asarray(column[rows[0]], float)
        other = np.asarray(drawn.series[renamed.get(name, name)][rows[1]], float)
        # the scale of its kind of quantity in the run: the largest column of its units (a round-off zero, the
        # teeth of an open clutch, is held to the run's forces, not to its own 1e-12 N)
        scale = max(np.max(np.abs(np.asarray(c, float))) for n, c in hoist.series.items()
                    if hoist.units.get(n) == hoist.units.get(name))
        allowed = rel * max(scale, 1e-300)
        if tighter is not None:
            allowed += 2.0 * np.max(np.abs(mine - np.asarray(tighter.series[name][rows[2]], float)))
        assert np.max(np.abs(mine - other)) <= allowed, name
    for name, value in hoist.values.items():
        if renamed.get(name, name) not in drawn.values and hoist.periodic is not None:
            continue  # the periodic regime's summary
        other = float(drawn.values[renamed.get(name, name)])
        allowed = rel * max(abs(float(value)), 1.0)
        if tighter is not None:
            allowed += 2.0 * abs(float(value) - float(tighter.values[name]))
        assert abs(float(value) - other) <= allowed or (value != value and other != other), name
    assert [str(k) for k in hoist.events["kind"]] == [str(k) for k in drawn.events["kind"]]


EVERY_PART = {  # a shipped hoist scenario for each part the template draws
    "exercise6_direct_start": 1e-12,  # motor, clutch, gears, drum, load, bearings
    "brake_stop_on_an_elastic_rope": 1e-12,  # a friction brake, an elastic rope
    "clutch_duty_cycle": 1e-12,  # the clutch's heating, its overheat
    "lift_and_run_back_through_a_lossy_mesh": 1e-12,  # a lossy mesh
    "lift_off_the_ground": 1e-12,  # the ground, a wire rope
    "engage_at_speed_with_brake": 1e-12,  # a holding brake
    "engage_at_speed_with_flywheel": 1e-12,  # a flywheel
    "engine_hoist_flywheel": 1e-12,  # both ripples, a flywheel: a periodic regime
    "slider_crank_press": 1e-12,  # a slider-crank: a periodic regime
}
# A periodic regime's rows (each period, each extreme of speed) end the hoist's steps where the drawing's run
# on: the two agree to the solver's accuracy, not to round-off.  How far the hoist is from the answer (these
# slip and relock every period) is measured beside it, against the hoist solved a thousand times tighter.
PERIODIC = {"simulation.duration": "4 s", "simulation.rtol": 1e-10, "simulation.atol": 1e-12}
TIGHTER = {**PERIODIC, "simulation.rtol": 1e-13, "simulation.atol": 1e-15}


@pytest.mark.parametrize("name", [pytest.param(name, marks=[] if name == "exercise6_direct_start" else pytest.mark.slow)
                                  for name in EVERY_PART])
def test_a_hoist_is_the_drivetrain_it_stands_for(name):
    hoist = load_scenario(SCENARIOS / f"{name}.yaml")
    tighter = None
    if hoist.periodic_regime is not None:
        hoist = load_scenario(SCENARIOS / f"{name}.yaml", overrides=PERIODIC)
        tighter = simulate(load_scenario(SCENARIOS / f"{name}.yaml", overrides=TIGHTER))
    data, renamed = hoist_as_drivetrain(hoist)
    _same_run(simulate(hoist), simulate(scenario_from_dict(data)), renamed, EVERY_PART[name], tighter)


def test_a_hoist_and_the_drivetrain_it_stands_for_are_one_program():
    """The machine runs under its parts' own names, in one order for every machine; a hoist's names are applied
    where its results are written.  So the hoist and its drawing (``check --drivetrain``) are served one
    compiled program: the second run compiles nothing, and each is written under its own names."""
    hoist = load_scenario(SCENARIOS / "exercise6_direct_start.yaml")
    data, renamed = hoist_as_drivetrain(hoist)
    with _jax.serving_recorded() as served:
        run = simulate(hoist)
        traced = loop.trace_count
        drawn = simulate(scenario_from_dict(data))
    assert loop.trace_count == traced and len(served) == 1  # one program, served twice
    assert {"slip_speed", "lockup_time"} <= set(run.series) | set(run.values)
    assert {"clutch_slip", "clutch_lockup_time", "pinion_speed"} <= set(drawn.series) | set(drawn.values)
    assert "clutch_slip" not in run.series and "pinion_speed" not in run.series  # the hoist's file as it was
    assert renamed["slip_speed"] == "clutch_slip"


def test_the_hoists_clutch_and_its_drawn_twins_are_drawn_alike_by_one_display():
    """One display draws every friction coupling: the hoist's clutch, read back under the names its file keeps
    (slip_speed, lockup_time), and the same clutch in the drivetrain the hoist stands for get the same panels of
    the same numbers, the same shading and the same story (the slip in rpm beside the hoist's speeds, in rad/s
    beside a drawn drivetrain's)."""
    from hoistsim.display.friction_clutch import FRICTION_CLUTCH
    from hoistsim.figures.read_back import prepared
    from hoistsim.results.run_dicts import run_dicts

    # pressed a little less than a start without slip needs: it slips, and at 0.1 kinetic friction never locks
    hoist = load_scenario(SCENARIOS / "exercise6_direct_start.yaml", overrides=["clutch.engagement_force=2580 N"])
    data, _ = hoist_as_drivetrain(hoist)
    runs = [prepared(run_dicts([simulate(scenario)])[0]) for scenario in (hoist, scenario_from_dict(data))]
    panels = [FRICTION_CLUTCH.panels_of(run) for run in runs]
    assert [p.name for p in panels[0]] == [p.name for p in panels[1]] == ["clutch_slips", "clutch_torque",
                                                                           "clutch_heats"]
    for ours, theirs in zip(*panels):
        assert [t.label for t in ours.traces] == [t.label for t in theirs.traces]
        for trace, twin in zip(ours.traces, theirs.traces):
            mine, other = trace.of(runs[0]), twin.of(runs[1])
            assert (mine is None) == (other is None)
            if mine is not None:
                np.testing.assert_allclose(mine, other, rtol=1e-9, atol=1e-9 * np.max(np.abs(other)))
    assert panels[0][0].ylabel.startswith("clutch slip [rpm]") and panels[1][0].ylabel.startswith("clutch slip [rad")
    assert [p.label for p in FRICTION_CLUTCH.shading_of(runs[0])] == ["clutch open", "clutch locked"]
    assert FRICTION_CLUTCH.shading_of(runs[0]) == FRICTION_CLUTCH.shading_of(runs[1])
    said = [FRICTION_CLUTCH.headline({**run["attrs"], "events": run["events"]}) for run in runs]
    assert said[0] == said[1] and said[0].startswith("clutch never locks (") and "kJ of heat" in said[0]


def test_a_ratchet_drawn_by_the_hoist_holds_as_a_drawn_one():
    """A ratchet (no shipped scenario has one) on the hoist and on its drawing: the same run."""
    base = load_scenario(SCENARIOS / "exercise6_direct_start.yaml")
    data = base.raw | {"ratchet": {"release_time": "1.5 s"}}
    data["clutch"] = {**data["clutch"], "engagement_force": [["0 s", "0 N"], ["0.5 s", "0 N"], ["0.6 s", "3201 N"]]}
    hoist = scenario_from_dict(data)
    drawn, renamed = hoist_as_drivetrain(hoist)
    assert drawn["drivetrain"]["ratchets"] == {"ratchet": {"release_time": "1.5 s", "shaft": "drum"}}
    _same_run(simulate(hoist), simulate(scenario_from_dict(drawn)), renamed, 1e-12)


def test_check_prints_the_drivetrain_a_hoist_stands_for():
    result = CliRunner().invoke(main, ["check", str(SCENARIOS / "clutch_duty_cycle.yaml"), "--drivetrain"])
    assert result.exit_code == 0, result.output
    assert "#   slip_speed -> clutch_slip" in result.output
    drawn = scenario_from_text(result.output)  # a scenario file as it is
    assert set(drawn.drivetrain.shafts) == {"motor", "pinion", "drum"}
    hoist = load_scenario(SCENARIOS / "clutch_duty_cycle.yaml")
    assert drawn.drivetrain.clutches["clutch"].heating == hoist.clutch_heating
    refused = CliRunner().invoke(main, ["check", str(SCENARIOS / "coupled_clutches.yaml"), "--drivetrain"])
    assert refused.exit_code == 2 and "drawn already" in refused.output


def test_brakes_on_two_shafts_stop_each_in_closed_form():
    """Two free shafts (2 and 5 kg*m^2 at 30 and -12 rad/s), each with a friction brake of 20 N*m applied at
    0.5 s: each stops J |w| / T after (3 s and 3 s), held after; each brake's heat is its shaft's energy."""
    run = simulate(_drawn(
        duration="4 s", shafts={"a": {"inertia": "2 kg*m^2", "speed": "30 rad/s"},
                                "b": {"inertia": "5 kg*m^2", "speed": "-12 rad/s"}},
        brakes={"stop_a": {"shaft": "a", "release_time": "0 s", "apply_time": "0.5 s", "static_torque": "25 N*m",
                           "kinetic_torque": "20 N*m"},
                "stop_b": {"shaft": "b", "release_time": "0 s", "apply_time": "0.5 s", "static_torque": "20 N*m"}}))
    t = run.time
    np.testing.assert_allclose(run["a_speed"], np.where(t < 0.5, 30.0, np.maximum(30.0 - 10.0 * (t - 0.5), 0.0)),
                               rtol=0, atol=1e-9)
    np.testing.assert_allclose(run["b_speed"], np.where(t < 0.5, -12.0, np.minimum(-12.0 + 4.0 * (t - 0.5), 0.0)),
                               rtol=0, atol=1e-9)
    assert run.values["stop_a_energy"] == pytest.approx(0.5 * 2 * 30**2, rel=1e-9)
    assert run.values["stop_b_energy"] == pytest.approx(0.5 * 5 * 12**2, rel=1e-9)
    sliding = (t > 0.6) & (t < 3.4)
    assert np.all(run["stop_a_torque"][sliding] == -20.0) and np.all(run["stop_b_torque"][sliding] == 20.0)
    kinds = {(str(k), str(e)) for k, e in zip(run.events["kind"], run.events["element"])}
    assert {("stop_a_apply", "stop_a"), ("lock", "stop_a"), ("lock", "stop_b")} <= kinds
    assert run.summary["energy_relative_residual"] < 1e-9


def test_a_pawl_holds_a_shaft_one_way():
    """A torque of -30 N*m on a shaft at rest with a pawl: held, the pawl passing +30 N*m; released at 1 s,
    the shaft runs backwards at -30 / 3 rad/s^2.  With +30 N*m it turns forwards freely from the start."""
    back = simulate(_drawn(shafts={"s": {"inertia": "3 kg*m^2"}}, torques=[{"shaft": "s", "torque": "-30 N*m"}],
                           ratchets={"pawl": {"shaft": "s", "release_time": "1 s"}}))
    t = back.time
    np.testing.assert_allclose(back["s_speed"], np.minimum(-10.0 * (t - 1.0), 0.0), rtol=0, atol=1e-9)
    assert np.all(back["pawl_torque"][t < 1.0] == 30.0) and np.all(back["pawl_engaged"][t < 1.0] == 1)
    ahead = simulate(_drawn(shafts={"s": {"inertia": "3 kg*m^2"}}, torques=[{"shaft": "s", "torque": "30 N*m"}],
                            ratchets={"pawl": {"shaft": "s"}}))
    np.testing.assert_allclose(ahead["s_speed"], 10.0 * ahead.time, rtol=0, atol=1e-9)


def test_a_drawn_clutch_heating_without_cooling_holds_its_slip_energy():
    """No cooling: C (T_end - T_0) is the clutch's slip energy, to round-off; the outputs carry its name."""
    run = simulate(_drawn(
        duration="6 s", shafts={"a": {"inertia": "1 kg*m^2", "speed": "20 rad/s"}, "b": {"inertia": "1 kg*m^2"}},
        clutches={"c": {"between": ["a", "b"], "static_friction": 0.3, "kinetic_friction": 0.2,
                        "effective_radius": "0.1 m", "force": "100 N",
                        "heating": {"heat_capacity": "50 J/K", "cooling": "0 W/K", "ambient_temperature": "20 degC"}}}))
    heat = run.values["c_slip_energy"]
    assert heat == pytest.approx(0.25 * 20**2, rel=1e-9)  # half the kinetic energy goes at a lock of equals
    assert run.values["final_c_temperature"] - 293.15 == pytest.approx(heat / 50.0, rel=1e-9)
    assert run.values["peak_c_temperature"] == pytest.approx(run.values["final_c_temperature"], rel=1e-12)
    assert "c_temperature" in run.series and "c_cooling_power" in run.series


def test_a_slider_crank_on_a_free_shaft_keeps_its_energy_over_the_angle():
    """A free shaft of 0.5 kg*m^2 at 20 rad/s with a slider-crank (2 kg, r 0.1 m, l 0.35 m): its speed at each
    angle is w0 sqrt((J + I(0)) / (J + I(a))) (no torque does work), with I(a) = m (dx/da)^2."""
    run = simulate(_drawn(shafts={"crank": {"inertia": "0.5 kg*m^2", "speed": "20 rad/s"}},
                          slider_cranks={"piston": {"shaft": "crank", "mass": "2 kg", "crank_radius": "0.1 m",
                                                    "rod_length": "0.35 m"}}))
    speed = run["crank_speed"]
    angle = np.concatenate([[0.0], np.cumsum(0.5 * (speed[1:] + speed[:-1]) * np.diff(run.time))])  # for I(a)
    inertia = run["piston_inertia"]
    r, l, a = 0.1, 0.35, angle
    ratio = -r * np.sin(a) - r**2 * np.sin(a) * np.cos(a) / np.sqrt(l**2 - (r * np.sin(a)) ** 2)
    np.testing.assert_allclose(inertia, 2.0 * ratio**2, rtol=0, atol=1e-5)  # the trapezoid's angle: 1e-5
    np.testing.assert_allclose(speed, 20.0 * np.sqrt(0.5 / (0.5 + inertia)), rtol=1e-9)
    np.testing.assert_allclose(run["piston_position"], r * np.cos(a) + np.sqrt(l**2 - (r * np.sin(a)) ** 2),
                               rtol=0, atol=1e-5)


def test_a_resisting_ripple_on_a_free_shaft_takes_its_work_over_the_angle():
    """A free shaft at 10 rad/s against 4 sin(a) N*m: 1/2 J w^2 = 1/2 J w0^2 - 4 (1 - cos a), at every row."""
    run = simulate(_drawn(shafts={"rotor": {"inertia": "1 kg*m^2", "speed": "10 rad/s",
                                            "resisting_ripple": {"harmonics": [{"order": 1, "amplitude": "4 N*m"}]}}}))
    # sin a from the torque, cos a from the energy the ripple has taken: (T/4)^2 + (1 - W/4)^2 = 1; the
    # speed's 1e-10 (the tolerance) squared into W = 1/2 (w0^2 - w^2) is some 2e-8 of it
    sine = run["rotor_resisting_ripple_torque"] / 4.0
    cosine = 1.0 - 0.5 * (100.0 - run["rotor_speed"] ** 2) / 4.0
    np.testing.assert_allclose(sine**2 + cosine**2, 1.0, rtol=0, atol=5e-8)
    assert cosine.min() < -0.99 and sine.min() < -0.99  # it went round: every angle met
    assert run.summary["energy_relative_residual"] < 1e-9


@pytest.mark.parametrize("parts, key, says", [
    ({"brakes": {"b": {"shaft": "nowhere", "release_time": "1 s"}}}, "drivetrain.brakes.b.shaft", "no shaft"),
    ({"brakes": {"b": {"shaft": "s", "release_time": "1 s"}}}, "drivetrain.brakes.b.static_torque", "holds shaft"),
    ({"ratchets": {"p": {"shaft": "s"}}}, "drivetrain.ratchets.p.shaft", "backwards"),
    ({"brakes": {"s": {"shaft": "s", "release_time": "1 s", "static_torque": "5 N*m"}}}, "drivetrain.brakes.s",
     "another part"),
    ({"brakes": {"b": {"shaft": "s", "release_time": "1 s", "kinetic_torque": "5 N*m"}}},
     "drivetrain.brakes.b.kinetic_torque", "needs static_torque"),
    ({"load": {"mass": "10 kg", "shaft": "s", "rope_radius": "0.1 m",
               "bearings": {"gear_offset": "0.1 m", "rope_offset": "0.2 m", "span": "0.5 m",
                            "wheel_pitch_diameter": "0.3 m"}}}, "drivetrain.load.bearings", "gear stage"),
    ({"load": {"mass": "0 kg", "shaft": "s", "rope_radius": "0.1 m", "rope": {"stiffness": "1 MN/m"}}},
     "drivetrain.load.mass", "positive"),
    ({"rotors": {"r": {"shaft": "s"}}}, "drivetrain.rotors.r.inertia", "required"),
])
def test_a_drawn_part_refuses_bad_input_naming_its_key(parts, key, says):
    with pytest.raises(ScenarioError) as err:
        _drawn(shafts={"s": {"inertia": "1 kg*m^2", "speed": "-1 rad/s"}}, **parts)
    assert err.value.key == key and says in err.value.message


def test_a_drawn_clutch_heating_refuses_a_kinetic_friction_above_the_static():
    with pytest.raises(ScenarioError) as err:
        _drawn(shafts={"a": {"inertia": "1 kg*m^2"}, "b": {"inertia": "1 kg*m^2"}},
               clutches={"c": {"between": ["a", "b"], "static_friction": 0.3, "kinetic_friction": 0.2,
                               "effective_radius": "0.1 m", "force": "100 N",
                               "heating": {"heat_capacity": "50 J/K", "cooling": "1 W/K", "ambient_temperature": "300 K",
                                           "kinetic_friction": [["300 K", 0.2], ["400 K", 0.35]]}}})
    assert err.value.key == "drivetrain.clutches.c.heating.kinetic_friction"
    assert math.isfinite(0.35) and "above the static friction" in err.value.message

"""Scenario loading: units converted to SI once, overrides, sweeps, and errors that
name the dotted key with the file and line.  No simulation here: fast."""

from __future__ import annotations

import copy
import dataclasses
import math
import pickle
import re

import pytest
from helpers import BASE, EXERCISE6_FILE, SCENARIOS, SHIPPED, line_of
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from hoistsim.scenario import units as u
from hoistsim.scenario.keys import parse_override
from hoistsim.scenario.loading import ScenarioError, load_scenario, scenario_from_dict, scenario_from_text
from hoistsim.scenario.sweep_runs import sweep_values

RPM = 2.0 * math.pi / 60.0


def edit(old: str, new: str, text: str = BASE) -> str:
    assert old in text, f"{old!r} is not in the base scenario"
    return text.replace(old, new, 1)


def error_for(text: str, **kwargs) -> ScenarioError:
    with pytest.raises(ScenarioError) as info:
        scenario_from_text(text, source="s.yaml", **kwargs)
    return info.value


# --------------------------------------------------------------------------------------
# units


@pytest.mark.parametrize("text, dimension, si", [
    ("200 daN", u.FORCE, 2000.0),
    ("3.201 kN", u.FORCE, 3201.0),
    ("300 rpm", u.ANGULAR_SPEED, 300 * RPM),
    ("5 rev/s", u.ANGULAR_SPEED, 10 * math.pi),
    ("2 rad/s", u.ANGULAR_SPEED, 2.0),
    ("25 deg", u.ANGLE, math.radians(25)),
    ("0.5 rad", u.ANGLE, 0.5),
    ("40 kg*m^2", u.INERTIA, 40.0),
    ("4000 kg*cm^2", u.INERTIA, 0.4),
    ("500 N*m", u.TORQUE, 500.0),
    ("20 cm", u.LENGTH, 0.2),
    ("4 mm", u.LENGTH, 0.004),
    ("500 kg", u.MASS, 500.0),
    ("1 ms", u.TIME, 1e-3),
    ("9.81 m/s^2", u.ACCELERATION, 9.81),
    ("30 %", u.DIMENSIONLESS, 0.3),
    ("1e-8", u.DIMENSIONLESS, 1e-8),
    ("2*250 kg", u.MASS, 500.0),
])
def test_text_with_units_is_converted_to_si(text, dimension, si):
    assert u.to_si(text, dimension) == pytest.approx(si, rel=1e-12)


@pytest.mark.parametrize("dimension", [u.ANGLE, u.ANGULAR_SPEED, u.FORCE, u.DIMENSIONLESS, u.INERTIA])
@pytest.mark.parametrize("number", [0, 3, 0.436, -1.5])
def test_bare_numbers_are_si(number, dimension):
    value = u.to_si(number, dimension)
    assert value == number and type(value) is float


@pytest.mark.parametrize("value, dimension, words", [
    ("300 kg", u.TORQUE, "expected a torque (like '500 N*m'), got '300 kg' which is a mass"),
    ("300 N*m", u.MASS, "got '300 N*m' which is a torque"),
    ("25 deg", u.DIMENSIONLESS, "which is an angle"),
    ("5 Hz", u.ANGULAR_SPEED, "which is a frequency; write it with an angle unit"),
    ("30 %", u.ANGLE, "which is a pure number"),
    ("20 degC", u.MASS, "which is a temperature"),
    ("500 kgg", u.MASS, "unknown unit 'kgg'"),
    ("heavy", u.MASS, "no number"),
    ("kg", u.MASS, "no number"),
    ("", u.MASS, "no number"),
    (True, u.DIMENSIONLESS, "yes/no value true"),
    (None, u.MASS, "no value given"),
    ([500], u.MASS, "got a list"),
    ({"value": 500}, u.MASS, "got a mapping"),
    (math.nan, u.MASS, "finite"),
    (math.inf, u.TIME, "finite"),
    ("nan kg", u.MASS, "finite"),
    ("-inf N*m", u.TORQUE, "finite"),
    ("1e400 kg", u.MASS, "finite"),
    # read by pint as something else, or as nothing: said in the writer's terms
    ("0,3", u.DIMENSIONLESS, "got '0,3': write decimals with a point, 0.3"),
    ("1,500 kg", u.MASS, "write decimals with a point, 1.500 kg, and thousands without a separator, 1500 kg"),
    ("500 Nm", u.TORQUE, "got '500 Nm': 'Nm' is read as number_meter, not N*m; write N*m (or N m), like '500 N*m'"),
    ("10 Nms/rad", u.TORSIONAL_DAMPING, "not N*m*s/rad; write N*m*s/rad, like '10 N*m*s/rad'"),
    ("1e4 Nm/rad", u.TORSIONAL_STIFFNESS, "write N*m/rad, like '1e4 N*m/rad'"),
    ("40 kgm^2", u.INERTIA, "unknown unit 'kgm': write kg*m^2, like '40 kg*m^2'"),
    ("95 mm2", u.AREA, "unknown unit 'mm2': write mm^2, like '95 mm^2'"),
    ("25 deg", u.TEMPERATURE, "'deg' is read as degree, not degC; write degC, like '25 degC'"),
    ("0.3 kg*m", u.DIMENSIONLESS, "read as 0.3 kilogram * meter, which is no pure number: write it as a plain number"),
    ("100 kg:900 kg", u.MASS, "got '100 kg:900 kg': one value, without ':'"),
])
def test_bad_quantities_say_what_was_expected(value, dimension, words):
    with pytest.raises(u.UnitError, match=None) as info:
        u.to_si(value, dimension)
    assert words in str(info.value)
    assert not re.search(r"\[(mass|length|time|temperature)\]", str(info.value)), info.value  # never pint's words


def test_limits_are_stated_in_the_users_terms():
    with pytest.raises(u.UnitError, match=r"must be less than 90 deg, got '90 deg'"):
        u.check_range(math.pi / 2, "90 deg", u.ANGLE, gt=0.0, lt=math.pi / 2)
    with pytest.raises(u.UnitError, match=r"got 2 rad \(= 114.592 deg\)"):
        u.check_range(2.0, 2, u.ANGLE, lt=math.pi / 2)
    with pytest.raises(u.UnitError, match="must not be negative, got -5 kg"):
        u.check_range(-5.0, -5, u.MASS, ge=0.0)
    assert u.check_range(0.0, 0, u.MASS, ge=0.0) == 0.0


# --------------------------------------------------------------------------------------
# the shipped scenario, in SI


def test_shipped_scenario_is_read_in_si():
    s = load_scenario(EXERCISE6_FILE)
    assert s.name == "exercise6-direct-start"
    assert s.source == str(EXERCISE6_FILE)
    assert s.text == SHIPPED
    assert s.motor.stall_torque == 500.0
    assert s.motor.no_load_speed == pytest.approx(31.41592653589793, rel=1e-12)
    assert s.motor.moment_of_inertia == pytest.approx(0.9, rel=1e-12)  # 40 kg * (15 cm)^2
    c = s.clutch
    assert (c.inner_radius, c.outer_radius) == pytest.approx((0.20, 0.24))
    assert c.half_angle == pytest.approx(math.radians(25.0))
    assert (c.static_friction, c.kinetic_friction, c.surfaces) == (0.3, 0.1, 1)
    assert c.engagement_force.times == (0.0,) and c.engagement_force.forces == (3201.0,)
    assert c.engagement_force.is_constant
    g = s.gears
    assert (g.pinion_teeth, g.wheel_teeth) == (17, 90) and isinstance(g.pinion_teeth, int)
    assert g.module == pytest.approx(0.004) and g.pressure_angle == pytest.approx(math.radians(20.0))
    assert s.drum.diameter == pytest.approx(0.4) and s.drum.inertia == 40.0
    assert s.load.mass == 500.0 and s.gravity == 9.81
    assert s.simulation.duration == 3.0 and s.simulation.output_interval == pytest.approx(1e-3)
    assert s.simulation.rtol == 1e-8 and type(s.simulation.rtol) is float  # YAML 1.2: 1e-8 is a number
    assert s.simulation.atol == 1e-10 and s.simulation.solver == "tsit5"
    assert s.sweep is None


def test_optional_sections_default_to_absent():
    s = scenario_from_text(BASE)
    assert s.brake is None and s.bearings is None and s.sweep is None
    assert (s.initial.motor_speed, s.initial.drum_speed) == (0.0, 0.0)


@pytest.mark.parametrize("path", sorted(SCENARIOS.rglob("*.yaml")), ids=lambda p: str(p.relative_to(SCENARIOS)))
def test_every_shipped_scenario_loads(path):
    """... and says what it means: no bare number on a key with a unit, no value outside what its part measures
    (each would be a warning, and an error under --strict)."""
    s = load_scenario(path, strict=True)
    assert s.warnings == []
    assert s.resolved()["name"] == s.name
    assert all(label == "" or "=" in label for label, _ in sweep_values(s))


def test_inertia_given_directly_or_by_rotor_mass_and_radius_of_gyration():
    direct = edit("  rotor_mass: 40 kg\n  radius_of_gyration: 15 cm\n", "  inertia: 0.9 kg*m^2\n")
    assert scenario_from_text(direct).motor.moment_of_inertia == 0.9
    assert scenario_from_text(BASE).motor.moment_of_inertia == pytest.approx(0.9)


def test_strict_raises_every_bare_number_at_once():
    """Under strict loading the error raised is the first value's, each other one in its ``also``, in the
    file's order: a caller says them all."""
    text = edit("  mass: 500 kg", "  mass: 500", edit("no_load_speed: 300 rpm", "no_load_speed: 31.4"))
    with pytest.raises(ScenarioError) as info:
        scenario_from_text(text, source="s.yaml", strict=True)
    said = info.value.each()
    assert [(e.key, e.line) for e in said] == [("motor.no_load_speed", line_of(text, "no_load_speed")),
                                               ("load.mass", line_of(text, "  mass: 500"))]
    assert all(e.source == "s.yaml" and e.message.endswith("(an error under --strict)") for e in said)


def test_bare_numbers_in_a_scenario_are_si():
    text = edit("no_load_speed: 300 rpm", "no_load_speed: 31.4")
    text = edit("half_angle: 25 deg", "half_angle: 0.4363", text)
    text = edit("engagement_force: 3201 N", "engagement_force: 3201", text)
    s = scenario_from_text(text)
    assert (s.motor.no_load_speed, s.clutch.half_angle, s.clutch.engagement_force.forces) == (31.4, 0.4363, (3201.0,))


@pytest.mark.parametrize("written", ["1e-8", "1.0e-8", "1E-8", "0.00000001", "'1e-8'"])
def test_exponents_are_numbers(written):
    s = scenario_from_text(edit("rtol: 1e-8", f"rtol: {written}"))
    assert s.simulation.rtol == pytest.approx(1e-8, rel=1e-15)


def test_whole_float_tooth_count_is_accepted():
    assert scenario_from_text(edit("pinion_teeth: 17", "pinion_teeth: 17.0")).gears.pinion_teeth == 17


def test_engagement_force_table_with_a_step():
    table = "[[0 s, 0 N], [0.5 s, 0 N], [0.5 s, 3 kN], [1500 ms, 300 daN]]"
    force = scenario_from_text(edit("engagement_force: 3201 N", f"engagement_force: {table}")).clutch.engagement_force
    assert force.times == (0.0, 0.5, 0.5, 1.5)
    assert force.forces == (0.0, 0.0, 3000.0, 3000.0)
    assert not force.is_constant


def test_engagement_force_table_in_block_style():
    block = "engagement_force:\n    - [0 s, 0 N]\n    - [0.5 s, 2000 N]"
    force = scenario_from_text(edit("engagement_force: 3201 N", block)).clutch.engagement_force
    assert (force.times, force.forces) == ((0.0, 0.5), (0.0, 2000.0))


def test_optional_sections():
    text = (BASE + "brake:\n  release_time: 0.5 s\n"
            "bearings:\n  gear_offset: 20 cm\n  rope_offset: 40 cm\n  span: 80 cm\n")
    s = scenario_from_text(text)
    assert s.brake.release_time == 0.5
    assert (s.bearings.gear_offset, s.bearings.rope_offset, s.bearings.span) == pytest.approx((0.2, 0.4, 0.8))


def test_resolved_is_plain_si_data():
    resolved = scenario_from_text(BASE + "sweep:\n  load.mass: [1 kg]\n").resolved()
    assert "sweep" not in resolved
    assert resolved["motor"]["no_load_speed"] == pytest.approx(10 * math.pi)
    assert resolved["clutch"]["engagement_force"] == {"times": [0.0], "forces": [3201.0]}


def test_scenario_from_dict():
    s = scenario_from_dict({**_plain_base(), "name": "from-python"})
    assert s.name == "from-python" and s.motor.no_load_speed == pytest.approx(10 * math.pi)


def _plain_base() -> dict:
    return scenario_from_text(BASE).raw


# --------------------------------------------------------------------------------------
# overrides


def test_set_overrides_a_scalar_and_is_noted_in_the_text():
    s = load_scenario(EXERCISE6_FILE, overrides=["clutch.engagement_force=200 daN", "load.mass = 600 kg"])
    assert s.clutch.engagement_force.forces == (2000.0,)
    assert s.load.mass == 600.0
    assert s.raw["clutch"]["engagement_force"] == "200 daN"
    assert "--set clutch.engagement_force" in s.text and s.text.startswith(SHIPPED.rstrip("\n"))


def test_set_can_add_an_optional_section_and_a_table():
    s = scenario_from_text(BASE, overrides={"brake.release_time": "0.4 s",
                                            "clutch.engagement_force": [["0 s", "0 N"], ["1 s", "2 kN"]]})
    assert s.brake.release_time == 0.4
    assert s.clutch.engagement_force.forces == (0.0, 2000.0)


def test_set_motor_inertia_replaces_rotor_mass_and_radius_of_gyration():
    s = load_scenario(EXERCISE6_FILE, overrides=["motor.inertia=1.2 kg*m^2"])
    assert s.motor.moment_of_inertia == 1.2 and s.motor.rotor_mass is None


@pytest.mark.parametrize("assignment, key, value", [
    ("clutch.engagement_force=2500 N", "clutch.engagement_force", "2500 N"),
    ("load.mass=500", "load.mass", 500),
    ("simulation.rtol=1e-6", "simulation.rtol", 1e-6),
    ("clutch.engagement_force=[[0 s, 0 N], [1 s, 1 kN]]", "clutch.engagement_force", [["0 s", "0 N"], ["1 s", "1 kN"]]),
    ("name=x=y", "name", "x=y"),
])
def test_parse_override(assignment, key, value):
    assert parse_override(assignment) == (key, value)


# --------------------------------------------------------------------------------------
# sweeps


def test_no_sweep_is_one_unlabelled_run():
    s = scenario_from_text(BASE)
    assert sweep_values(s) == [("", s)]


def test_sweep_of_one_key():
    s = scenario_from_text(BASE + "sweep:\n  clutch.engagement_force: [1000 N, 2000 N, 3201 N]\n")
    runs = sweep_values(s)
    assert [label for label, _ in runs] == [
        "clutch.engagement_force=1000 N", "clutch.engagement_force=2000 N", "clutch.engagement_force=3201 N"]
    assert [run.clutch.engagement_force.forces for _, run in runs] == [(1000.0,), (2000.0,), (3201.0,)]
    for _, run in runs:
        assert run.sweep is None and "sweep" not in run.raw
        assert run.text == s.text and run.source == s.source
        assert run.load.mass == 500.0


def test_sweep_of_two_keys_is_a_grid():
    s = scenario_from_text(BASE + "sweep:\n  load.mass: [100 kg, 500 kg]\n"
                                  "  clutch.engagement_force: [1 kN, 2 kN, 3 kN]\n")
    runs = sweep_values(s)
    assert len(runs) == 6
    assert [(r.load.mass, r.clutch.engagement_force.forces[0]) for _, r in runs] == [
        (m, f) for m in (100.0, 500.0) for f in (1000.0, 2000.0, 3000.0)]
    assert runs[0][0] == "load.mass=100 kg, clutch.engagement_force=1 kN"
    assert runs[-1][0] == "load.mass=500 kg, clutch.engagement_force=3 kN"


def test_sweep_of_tables_and_numbers():
    s = scenario_from_text(BASE + "sweep:\n  clutch.engagement_force: [[[0 s, 0 N], [0.5 s, 3 kN]], 1000]\n")
    (label_a, a), (label_b, b) = sweep_values(s)
    assert a.clutch.engagement_force.times == (0.0, 0.5) and b.clutch.engagement_force.forces == (1000.0,)
    assert label_a == 'clutch.engagement_force=[["0 s","0 N"],["0.5 s","3 kN"]]'
    assert label_b == "clutch.engagement_force=1000"


def test_sweep_of_motor_inertia_on_a_scenario_with_rotor_mass():
    s = scenario_from_text(BASE + "sweep:\n  motor.inertia: [0.5 kg*m^2, 2 kg*m^2]\n")
    assert [r.motor.moment_of_inertia for _, r in sweep_values(s)] == [0.5, 2.0]


def test_what_loading_learns_is_one_frozen_provenance_that_copies_and_pickles_keep():
    s = scenario_from_text(BASE + "sweep:\n  load.mass: [100 kg, 500 kg]\n", source="s.yaml",
                           overrides={"brake.release_time": "0.4 s"})
    learnt = s.provenance
    assert (learnt.source, learnt.overridden, list(learnt.swept)) == ("s.yaml", {"brake.release_time"}, ["load.mass"])
    assert learnt.text == s.text and "--set brake.release_time" in s.text and learnt.raw == s.raw
    mass = learnt.swept["load.mass"]
    assert list(mass.labels) == ["100 kg", "500 kg"] and list(mass.numbers) == [100.0, 500.0]
    assert list(mass.validated) == [100.0, 500.0]
    with pytest.raises(dataclasses.FrozenInstanceError):
        learnt.text = ""
    for kept in (s.model_copy(), copy.deepcopy(s), pickle.loads(pickle.dumps(s))):  # a sweep sent to workers
        assert (kept.text, kept.source, kept.raw, kept.warnings) == (s.text, s.source, s.raw, s.warnings)
        assert list(kept.provenance.swept["load.mass"].labels) == ["100 kg", "500 kg"]
    (_, light), _ = sweep_values(s)
    assert light.provenance.swept == {} and light.provenance.overridden == learnt.overridden
    assert light.raw["load"]["mass"] == "100 kg" and light.raw["brake"] == {"release_time": "0.4 s"}


# --------------------------------------------------------------------------------------
# errors: the key, the file and the line


def test_error_has_key_source_line_and_one_line_text():
    text = edit("static_friction: 0.3", "static_friciton: 0.3")
    err = error_for(text)
    assert err.key == "clutch.static_friciton"
    assert err.source == "s.yaml" and err.line == line_of(text, "static_friciton")
    assert str(err) == f"s.yaml:{err.line}: clutch.static_friciton: unknown key (did you mean clutch.static_friction?); every key: docs/scenario.md"
    assert isinstance(err, ValueError)


@pytest.mark.parametrize("old, new, key, at, words", [
    ("mass: 500 kg", "mass: 300 N*m", "load.mass", "  mass:", "expected a mass (like '500 kg'), got '300 N*m'"),
    ("stall_torque: 500 N*m", "stall_torque: 300 kg", "motor.stall_torque", "stall_torque",
     "expected a torque (like '500 N*m'), got '300 kg' which is a mass"),
    ("mass: 500 kg", "mass: -5 kg", "load.mass", "  mass:", "must not be negative"),
    ("duration: 3 s", "duration: 0 s", "simulation.duration", "duration", "must be positive"),
    ("mass: 500 kg", "mass: .nan", "load.mass", "  mass:", "finite"),
    ("duration: 3 s", "duration: .inf", "simulation.duration", "duration", "finite"),
    ("mass: 500 kg", "mass: nan kg", "load.mass", "  mass:", "finite"),
    ("kinetic_friction: 0.1", "kinetic_friction: 0.4", "clutch.kinetic_friction", "kinetic_friction",
     "must not exceed static_friction (0.3)"),
    ("inner_radius: 20 cm", "inner_radius: 30 cm", "clutch.inner_radius", "inner_radius", "outer_radius"),
    ("static_friction: 0.3", "static_friction: true", "clutch.static_friction", "static_friction", "yes/no"),
    ("pinion_teeth: 17", "pinion_teeth: 17.5", "gears.pinion_teeth", "pinion_teeth", "whole number of teeth"),
    ("half_angle: 25 deg", "half_angle: 90 deg", "clutch.half_angle", "half_angle", "less than 90 deg"),
    ("engagement_force: 3201 N", "engagement_force: [[0 s, 0 N], [0.5 s, 0 N], [0.4 s, 3000 N]]",
     "clutch.engagement_force", "engagement_force", "row 3: time goes backwards (0.4 s after 0.5 s)"),
    ("  diameter: 40 cm\n", "", "drum.diameter", "drum:", "required value is missing"),
    ("  mass: 500 kg", "  mass: 500 kg\n  mass: 600 kg", "load.mass", "mass: 600",
     "duplicate key (first given at line"),
    ("mass: 500 kg", "mass: [500 kg", "load.mass", "mass: [", "malformed YAML: a '[' list is not closed"),
    ("  rotor_mass: 40 kg\n", "  rotor_mass: 40 kg\n  inertia: 1 kg*m^2\n", "motor.inertia", "inertia: 1", "not both"),
])
def test_errors_name_key_and_line(old, new, key, at, words):
    text = edit(old, new)
    err = error_for(text)
    assert (err.key, err.line, err.source) == (key, line_of(text, at), "s.yaml")
    assert words in err.message
    assert str(err).startswith(f"s.yaml:{err.line}: {key}: ")


def test_table_row_errors_point_at_the_row():
    text = edit("engagement_force: 3201 N", "engagement_force:\n    - [0 s, 0 N]\n    - [0.5 s, -3 N]")
    err = error_for(text)
    assert err.key == "clutch.engagement_force" and err.line == line_of(text, "- [0.5 s")
    assert "row 2" in err.message and "pushed apart" in err.message


def test_missing_section_has_no_line():
    err = error_for(edit("drum:\n  diameter: 40 cm\n  inertia: 40 kg*m^2\n", ""))
    assert (err.key, err.line) == ("drum", None)
    assert str(err) == "s.yaml: drum: required section is missing"


@pytest.mark.parametrize("text", ["", "\n", "# only a comment\n"])
def test_empty_scenario(text):
    err = error_for(text)
    assert "empty" in str(err) and err.key == ""


def test_missing_file(tmp_path):
    with pytest.raises(ScenarioError, match="no such scenario file"):
        load_scenario(tmp_path / "nope.yaml")
    with pytest.raises(ScenarioError, match="folder"):
        load_scenario(tmp_path)


@pytest.mark.parametrize("assignment, key, words", [
    ("laod.mass=3 kg", "laod", "did you mean load?"),
    ("load.mas=3 kg", "load.mas", "did you mean load.mass?"),
    ("load.mass=3 m", "load.mass", "which is a length"),
    ("clutch.static_friction=.nan", "clutch.static_friction", "finite"),
    ("load=3", "load", "is a section"),
    ("sweep.load.mass=[1 kg]", "sweep", "cannot be given with --set"),
])
def test_override_errors_name_the_key_and_set(assignment, key, words):
    err = error_for(BASE, overrides=[assignment])
    assert (err.key, err.source, err.line) == (key, "--set", None)
    assert words in err.message and str(err).startswith(f"--set: {key}: ")


def test_override_of_a_swept_key_is_an_error():
    err = error_for(BASE + "sweep:\n  load.mass: [1 kg, 2 kg]\n", overrides=["load.mass=3 kg"])
    assert err.key == "load.mass" and "swept" in err.message


@pytest.mark.parametrize("sweep, key, words", [
    ("clutch.engagment_force: [1 kN]", "sweep.clutch.engagment_force", "did you mean clutch.engagement_force?"),
    ("clutch: [1 kN]", "sweep.clutch", "is a section"),
    ("load.mass: []", "sweep.load.mass", "non-empty list"),
    ("load.mass: 3 kg", "sweep.load.mass", "non-empty list"),
    ("load.mass: [1 kg, 2 N]", "sweep.load.mass", "value 2 (2 N): expected a mass"),
])
def test_sweep_errors(sweep, key, words):
    text = BASE + f"sweep:\n  {sweep}\n"
    err = error_for(text)
    assert (err.key, err.line) == (key, line_of(text, sweep))
    assert words in err.message


def test_error_message_is_always_one_line():
    err = ScenarioError("a.b", "first\nsecond", source="s.yaml", line=3)
    assert str(err) == "s.yaml:3: a.b: first second"


# --------------------------------------------------------------------------------------
# robustness: whatever is written, the answer is a scenario or a ScenarioError

TRICKY = ["", "~", "true", "no", ".nan", "-.inf", "1e-8", "1e400", "0", "-0", "17.5", "[]", "{}", "[1, 2]",
          "[[0 s, 1 N]]", "'", '"', "[", "{", ": :", "&a", "*a", "!!binary AA", "!tag 3", "2024-01-01",
          "300 rpm", "3 kg", "25 deg", "nan kg", "5 Hz", "1e3 N", "0x10", "1_000", "- a", "\t3", "10^3 N",
          "kg", "%", "3 %", "?", "|", ">", "# comment", "1 m/s^2", "-1 s", "0.9 kg*m^2"]
LINES = SHIPPED.splitlines()


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(line=st.integers(0, len(LINES) - 1),
       value=st.one_of(st.sampled_from(TRICKY), st.text(max_size=12)),
       action=st.sampled_from(["value", "line", "insert", "delete"]))
def test_any_edit_gives_a_scenario_or_a_scenario_error(line, value, action):
    lines = list(LINES)
    if action == "value" and ":" in lines[line]:
        lines[line] = lines[line].split(":", 1)[0] + ": " + value
    elif action == "line":
        lines[line] = value
    elif action == "insert":
        lines.insert(line, value)
    else:
        del lines[line]
    try:
        scenario_from_text("\n".join(lines) + "\n", source="s.yaml")
    except ScenarioError as err:
        assert "\n" not in str(err) and str(err).startswith("s.yaml")


@pytest.mark.parametrize("dimension, units", [
    ("FORCE", ["N", "kN", "daN", "lbf"]), ("ANGULAR_SPEED", ["rpm", "rad/s", "deg/s"]),
    ("INERTIA", ["kg*m^2", "g*cm^2", "lb*ft^2"]), ("LENGTH", ["m", "cm", "mm", "in"])])
def test_a_number_with_a_unit_reads_as_pint_reads_it(dimension, units):
    """The quick reading of "6543.21 N" (the number times the unit's SI value, the unit judged once) gives
    pint's value, bit for bit, and pint's message for a unit of another dimension."""
    import random

    from hoistsim.scenario import units as u

    rnd = random.Random(7)
    dim = getattr(u, dimension)
    for _ in range(400):
        text = f"{rnd.uniform(-1e5, 1e5):.{rnd.randint(0, 12)}g} {rnd.choice(units)}"
        u._string_to_si.cache_clear()
        assert u.to_si(text, dim) == u._to_si(text, dim), text
    with pytest.raises(u.UnitError, match="which is"):
        u.to_si("3 s", dim)


def test_a_large_listed_sweep_reads_without_the_round_trip_tree_and_errors_still_name_lines():
    """The data of a file is read by the C parser; the round-trip tree (lines) only for a message."""
    from hoistsim.scenario import yamlsource

    tables = "".join(f"\n    - [[0 s, 0 N], [0.05 s, {3000 + i} N]]" for i in range(50))
    good = scenario_from_text(BASE + "sweep:\n  clutch.engagement_force:" + tables + "\n")
    assert len(sweep_values(good)) == 50
    bad = BASE + "sweep:\n  clutch.engagement_force:" + tables + "\n    - [[0 s, 0 N], [0.05 s, -1 N]]\n"
    with pytest.raises(ScenarioError) as err:
        scenario_from_text(bad, source="s.yaml")
    assert err.value.line == bad.count("\n") and "value 51" in err.value.message
    assert isinstance(yamlsource.read_yaml(BASE, "s.yaml").data, dict)
    assert yamlsource.read_yaml(BASE, "s.yaml")._tree is None  # no round-trip parse unless asked


def test_a_swept_keys_unit_is_found_through_a_drawn_parts_name():
    """The unit a swept key's values are written in (a results file's attribute, compare's header): the hoist's
    keys and a drawn part's, through its name or a list's index."""
    from hoistsim.scenario.keys import key_units

    assert key_units("clutch.engagement_force") == "N" and key_units("load.mass") == "kg"
    assert key_units("drivetrain.shafts.J1.inertia") == "kg*m^2"
    assert key_units("drivetrain.springs.spring.stiffness") == "N*m/rad"
    assert key_units("drivetrain.torques.1.torque") == "N*m"
    assert key_units("clutch.static_friction") == "" and key_units("no.such.key") == ""

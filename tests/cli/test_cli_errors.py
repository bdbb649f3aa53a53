"""Bad input through the command line: exit status 2, one line on stderr that names
the dotted key (and the line, where the YAML parser knows it), no traceback, and
nothing written.  Every case fails before any simulation; a guard makes sure."""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import dataclass

import pytest
from click.testing import CliRunner
from helpers import BASE, EXERCISE6_FILE, line_of

from hoistsim.cli import main
from hoistsim.running import simulation
from hoistsim.studies import flywheel  # imported before any test patches the simulation away

TABLE = "engagement_force: 3201 N"
MOTOR_GEOMETRY = "  rotor_mass: 40 kg\n  radius_of_gyration: 15 cm\n"

HEATING = "clutch_heating:\n  heat_capacity: 2.4 kJ/K\n  cooling: 20 W/K\n  ambient_temperature: 25 degC\n"


@dataclass(frozen=True)
class Case:
    id: str
    old: str | None  # text of the base scenario to replace; None: append ``new``; "*": the whole file
    new: str
    key: str  # dotted key the message must name ("" where there is none)
    at: str | None = None  # the message names the line holding this text (None: no line)
    words: str = ""  # and contains these words

    def text(self) -> str:
        if self.old == "*":
            return self.new
        if self.old is None:
            return BASE + self.new
        assert self.old in BASE, f"{self.old!r} is not in the base scenario"
        return BASE.replace(self.old, self.new, 1)


CASES = [
    # unknown and misspelt keys
    Case("misspelt key", "static_friction: 0.3", "static_friciton: 0.3", "clutch.static_friciton",
         "static_friciton", "did you mean clutch.static_friction?"),
    Case("misspelt top-level key", None, "gravty: 9.8 m/s^2\n", "gravty", "gravty", "did you mean gravity?"),
    Case("unknown section", None, "brakes:\n  release_time: 1 s\n", "brakes", "brakes:", "did you mean brake?"),
    Case("misspelt key in an optional section", None, "brake:\n  release_tim: 1 s\n", "brake.release_tim",
         "release_tim", "did you mean brake.release_time?"),
    Case("key in the wrong section", "  mass: 500 kg", "  mass: 500 kg\n  no_load_speed: 20 rpm",
         "load.no_load_speed", "no_load_speed: 20", "did you mean motor.no_load_speed?"),
    Case("unknown key with no near match", None, "colour: red\n", "colour", "colour", "known keys"),
    # wrong dimensions
    Case("torque for a mass", "mass: 500 kg", "mass: 300 N*m", "load.mass", "  mass:",
         "expected a mass (like '500 kg'), got '300 N*m' which is a torque"),
    Case("mass for a torque", "stall_torque: 500 N*m", "stall_torque: 300 kg", "motor.stall_torque",
         "stall_torque", "expected a torque (like '500 N*m'), got '300 kg' which is a mass"),
    Case("angle for a friction coefficient", "static_friction: 0.3", "static_friction: 25 deg",
         "clutch.static_friction", "static_friction", "which is an angle"),
    Case("frequency for an angular speed", "no_load_speed: 300 rpm", "no_load_speed: 5 Hz",
         "motor.no_load_speed", "no_load_speed", "frequency"),
    Case("length for a force", TABLE, "engagement_force: 3 m", "clutch.engagement_force", "engagement_force",
         "expected a force"),
    Case("unknown unit", "module: 4 mm", "module: 4 mmm", "gears.module", "module:", "unknown unit 'mmm'"),
    Case("text without a number", "mass: 500 kg", "mass: heavy", "load.mass", "  mass:", "no number"),
    Case("a list for a scalar", "mass: 500 kg", "mass: [500 kg]", "load.mass", "  mass:", "got a list"),
    # what pint reads otherwise than meant: said in the writer's terms, never as pint's dimensions
    Case("decimal comma", "static_friction: 0.3", "static_friction: 0,3", "clutch.static_friction",
         "static_friction", "got '0,3': write decimals with a point, 0.3"),
    Case("decimal comma with a unit", "mass: 500 kg", "mass: 1,5 kg", "load.mass", "  mass:",
         "got '1,5 kg': write decimals with a point, 1.5 kg"),
    Case("comma of thousands", "mass: 500 kg", "mass: 1,500 kg", "load.mass", "  mass:",
         "write decimals with a point, 1.500 kg, and thousands without a separator, 1500 kg"),
    Case("torque in Nm", "stall_torque: 500 N*m", "stall_torque: 500 Nm", "motor.stall_torque", "stall_torque",
         "got '500 Nm': 'Nm' is read as number_meter, not N*m; write N*m (or N m), like '500 N*m'"),
    Case("torque in kNm", "stall_torque: 500 N*m", "stall_torque: 0.5 kNm", "motor.stall_torque", "stall_torque",
         "write kN*m (or kN m), like '0.5 kN*m'"),
    Case("temperature in degrees of angle", None, HEATING.replace("25 degC", "25 deg"),
         "clutch_heating.ambient_temperature", "ambient_temperature", "'deg' is read as degree, not degC; write "
         "degC, like '25 degC'"),
    Case("inertia in kgm2", "inertia: 40 kg*m^2", "inertia: 40 kgm2", "drum.inertia", "inertia: 40",
         "unknown unit 'kgm2': write kg*m^2, like '40 kg*m^2'"),
    Case("inertia of another dimension", "inertia: 40 kg*m^2", "inertia: 40 kg*m", "drum.inertia", "inertia: 40",
         "got '40 kg*m', read as 40 kilogram * meter, which is no moment of inertia: write it in kg*m^2, like "
         "'40 kg*m^2'"),
    Case("a range for one value", "mass: 500 kg", "mass: 100 kg:900 kg", "load.mass", "  mass:",
         "got '100 kg:900 kg': one value, without ':' (a range of values is a sweep's: "
         "KEY=FROM:TO:COUNT on the command line, {from: ..., to: ..., count: ...} in a file's sweep:)"),
    # non-physical values
    Case("negative mass", "mass: 500 kg", "mass: -5 kg", "load.mass", "  mass:", "must not be negative"),
    Case("zero duration", "duration: 3 s", "duration: 0 s", "simulation.duration", "duration", "must be positive"),
    Case("negative radius", "inner_radius: 20 cm", "inner_radius: -20 cm", "clutch.inner_radius", "inner_radius",
         "must be positive"),
    Case("zero module", "module: 4 mm", "module: 0 mm", "gears.module", "module:", "must be positive"),
    Case("negative stall torque", "stall_torque: 500 N*m", "stall_torque: -500 N*m", "motor.stall_torque",
         "stall_torque", "must be positive"),
    Case("negative friction", "kinetic_friction: 0.1", "kinetic_friction: -0.1", "clutch.kinetic_friction",
         "kinetic_friction", "must not be negative"),
    Case("negative gravity", "gravity: 9.81 m/s^2", "gravity: -9.81 m/s^2", "gravity", "gravity", "negative"),
    Case("rtol of one or more", "rtol: 1e-8", "rtol: 2", "simulation.rtol", "rtol", "must be less than 1"),
    Case("zero atol", "atol: 1e-10", "atol: 0", "simulation.atol", "atol", "must be positive"),
    Case("rtol finer than float64 resolves", "rtol: 1e-8", "rtol: 1e-20", "simulation.rtol", "rtol",
         "must be at least 1e-14, got 1e-20"),
    Case("NaN in YAML", "mass: 500 kg", "mass: .nan", "load.mass", "  mass:", "finite"),
    Case("NaN in YAML, capitals", "stall_torque: 500 N*m", "stall_torque: .NaN", "motor.stall_torque",
         "stall_torque", "finite"),
    Case("infinity in YAML", "duration: 3 s", "duration: .inf", "simulation.duration", "duration", "finite"),
    Case("minus infinity in YAML", "static_friction: 0.3", "static_friction: -.inf", "clutch.static_friction",
         "static_friction", "finite"),
    Case("NaN with a unit", "mass: 500 kg", "mass: nan kg", "load.mass", "  mass:", "finite"),
    Case("infinity with a unit", "no_load_speed: 300 rpm", "no_load_speed: inf rpm", "motor.no_load_speed",
         "no_load_speed", "finite"),
    Case("overflow to infinity", "mass: 500 kg", "mass: 1e400 kg", "load.mass", "  mass:", "finite"),
    Case("integer too large for a float", "mass: 500 kg", "mass: 1" + "0" * 400, "load.mass", "  mass:", "finite"),
    Case("power of ten written with ^", "mass: 500 kg", "mass: 10^3 kg", "load.mass", "  mass:", "1e6"),
    Case("NaN friction as text", "static_friction: 0.3", "static_friction: nan", "clutch.static_friction",
         "static_friction", "finite"),
    Case("kinetic friction above static", "kinetic_friction: 0.1", "kinetic_friction: 0.4",
         "clutch.kinetic_friction", "kinetic_friction", "must not exceed static_friction (0.3)"),
    Case("inner radius not inside the outer", "inner_radius: 20 cm", "inner_radius: 24 cm", "clutch.inner_radius",
         "inner_radius", "must be less than outer_radius"),
    Case("half angle of 90 deg", "half_angle: 25 deg", "half_angle: 90 deg", "clutch.half_angle", "half_angle",
         "must be less than 90 deg"),
    Case("half angle above 90 deg", "half_angle: 25 deg", "half_angle: 115 deg", "clutch.half_angle", "half_angle",
         "must be less than 90 deg"),
    Case("half angle of 2 rad", "half_angle: 25 deg", "half_angle: 2", "clutch.half_angle", "half_angle",
         "114.592 deg"),
    Case("zero half angle", "half_angle: 25 deg", "half_angle: 0 deg", "clutch.half_angle", "half_angle",
         "must be positive"),
    Case("pressure angle of 90 deg", "pressure_angle: 20 deg", "pressure_angle: 90 deg", "gears.pressure_angle",
         "pressure_angle", "must be less than 90 deg"),
    Case("mesh efficiency above 1", "pressure_angle: 20 deg", "pressure_angle: 20 deg\n  efficiency: 1.03",
         "gears.efficiency", "efficiency", "must be at most 1"),
    Case("mesh efficiency of zero", "pressure_angle: 20 deg", "pressure_angle: 20 deg\n  efficiency: 0",
         "gears.efficiency", "efficiency", "must be positive"),
    Case("negative backdrive efficiency", "pressure_angle: 20 deg",
         "pressure_angle: 20 deg\n  backdrive_efficiency: -0.2", "gears.backdrive_efficiency", "backdrive_efficiency",
         "must be positive"),
    # clutch heating
    Case("zero heat capacity", None, HEATING.replace("2.4 kJ/K", "0 J/K"), "clutch_heating.heat_capacity",
         "heat_capacity", "must be positive"),
    Case("heat capacity in the wrong unit", None, HEATING.replace("2.4 kJ/K", "2.4 kJ"),
         "clutch_heating.heat_capacity", "heat_capacity", "expected a heat capacity"),
    Case("negative conductance", None, HEATING.replace("20 W/K", "-3 W/K"), "clutch_heating.cooling", "cooling",
         "must not be negative"),
    Case("ambient below absolute zero", None, HEATING.replace("ambient_temperature: 25 degC",
                                                              "ambient_temperature: -300 degC"),
         "clutch_heating.ambient_temperature", "ambient_temperature", "must be above absolute zero"),
    Case("initial temperature in kelvin below zero", None, HEATING + "  initial_temperature: -5 K\n",
         "clutch_heating.initial_temperature", "initial_temperature", "must be above absolute zero"),
    Case("friction table with temperatures going back", None,
         HEATING + "  static_friction: [[25 degC, 0.3], [300 degC, 0.25], [200 degC, 0.22]]\n",
         "clutch_heating.static_friction", "static_friction: [[25", "row 3: temperatures must increase"),
    Case("friction table with a negative kinetic friction", None,
         HEATING + "  kinetic_friction: [[25 degC, 0.1], [300 degC, -0.02]]\n", "clutch_heating.kinetic_friction",
         "kinetic_friction: [[25", "row 2: must not be negative"),
    Case("friction table in degrees of angle", None,
         HEATING + "  static_friction: [[25 deg, 0.3], [300 deg, 0.22]]\n", "clutch_heating.static_friction",
         "static_friction: [[25", "expected a temperature"),
    Case("kinetic friction above static when hot", None,
         HEATING + "  static_friction: [[25 degC, 0.3], [300 degC, 0.08]]\n", "clutch_heating.static_friction",
         "static_friction: [[25", "above the static friction 0.08 at 300 degC"),
    Case("kinetic table above static table between their knots", None,
         HEATING + "  static_friction: [[25 degC, 0.3], [300 degC, 0.1]]\n"
         "  kinetic_friction: [[100 degC, 0.1], [200 degC, 0.25]]\n", "clutch_heating.kinetic_friction",
         "kinetic_friction: [[100", "above the static friction"),
    Case("max temperature below the start", None, HEATING + "  max_temperature: 20 degC\n",
         "clutch_heating.max_temperature", "max_temperature", "must be above the initial temperature (25 degC)"),
    Case("efficiency as a percentage", "pressure_angle: 20 deg", "pressure_angle: 20 deg\n  efficiency: 97",
         "gears.efficiency", "efficiency", "must be at most 1"),
    Case("output interval longer than the run", "output_interval: 1 ms", "output_interval: 5 s",
         "simulation.output_interval", "output_interval", "must not exceed the duration"),
    Case("drum moving while the brake holds it", None, "brake:\n  release_time: 1 s\ninitial:\n  drum_speed: 3 rpm\n",
         "initial.drum_speed", "drum_speed", "holding brake"),
    Case("steady lift and a speed", None, "initial:\n  steady_lift: true\n  motor_speed: 100 rpm\n",
         "initial.motor_speed", "motor_speed", "not both"),
    Case("steady lift against the brake", None, "brake:\n  release_time: 1 s\ninitial:\n  steady_lift: true\n",
         "initial.steady_lift", "steady_lift", "brake"),
    Case("brake slipping above its static torque", None,
         "brake:\n  release_time: 1 s\n  static_torque: 1000 N*m\n  kinetic_torque: 1200 N*m\n",
         "brake.kinetic_torque", "kinetic_torque", "must not exceed static_torque"),
    Case("brake kinetic torque alone", None, "brake:\n  release_time: 1 s\n  kinetic_torque: 800 N*m\n",
         "brake.kinetic_torque", "kinetic_torque", "needs static_torque"),
    Case("brake applied before it is released", None,
         "brake:\n  release_time: 1 s\n  static_torque: 1000 N*m\n  apply_time: 0.5 s\n",
         "brake.apply_time", "apply_time", "must be after release_time"),
    Case("holding brake applied again", None, "brake:\n  release_time: 1 s\n  apply_time: 2 s\n",
         "brake.apply_time", "apply_time", "needs static_torque"),
    # booleans, counts, text
    Case("boolean for a number", "static_friction: 0.3", "static_friction: true", "clutch.static_friction",
         "static_friction", "yes/no value true"),
    Case("boolean for a torque", "stall_torque: 500 N*m", "stall_torque: false", "motor.stall_torque",
         "stall_torque", "yes/no value false"),
    Case("'yes' for a number", "static_friction: 0.3", "static_friction: yes", "clutch.static_friction",
         "static_friction", "expected a pure number"),
    Case("boolean for a tooth count", "pinion_teeth: 17", "pinion_teeth: true", "gears.pinion_teeth",
         "pinion_teeth", "whole number"),
    Case("fractional tooth count", "pinion_teeth: 17", "pinion_teeth: 17.5", "gears.pinion_teeth", "pinion_teeth",
         "must be a whole number of teeth, got 17.5"),
    Case("tooth count as text", "wheel_teeth: 90", "wheel_teeth: ninety", "gears.wheel_teeth", "wheel_teeth",
         "whole number"),
    Case("zero teeth", "wheel_teeth: 90", "wheel_teeth: 0", "gears.wheel_teeth", "wheel_teeth", "at least 1"),
    Case("no friction surfaces", "surfaces: 1", "surfaces: 0", "clutch.surfaces", "surfaces", "at least 1"),
    Case("unknown solver", "solver: tsit5", "solver: euler", "simulation.solver", "solver", "'tsit5'"),
    Case("name that is not text", "name: exercise6-direct-start", "name: [a, b]", "name", "name:", "must be text"),
    Case("empty name", "name: exercise6-direct-start", "name: ''", "name", "name:", "must not be empty"),
    # missing sections and values
    Case("missing section", "drum:\n  diameter: 40 cm\n  inertia: 40 kg*m^2\n", "", "drum", None,
         "required section is missing"),
    Case("missing name", "name: exercise6-direct-start\n", "", "name", None, "required value is missing"),
    Case("missing value", "  diameter: 40 cm\n", "", "drum.diameter", "drum:", "required value is missing"),
    Case("empty value", "mass: 500 kg", "mass:", "load.mass", "  mass:", "no value given"),
    Case("empty section", "load:\n  mass: 500 kg\n", "load:\n", "load", "load:", "the section is empty"),
    Case("value for a section", "load:\n  mass: 500 kg\n", "load: 500 kg\n", "load", "load:", "must be a section"),
    Case("no motor inertia", MOTOR_GEOMETRY, "", "motor.inertia", "motor:", "rotor_mass and radius_of_gyration"),
    Case("rotor mass without radius of gyration", MOTOR_GEOMETRY, "  rotor_mass: 40 kg\n",
         "motor.radius_of_gyration", "motor:", "required"),
    Case("two motor inertias", MOTOR_GEOMETRY, MOTOR_GEOMETRY + "  inertia: 0.9 kg*m^2\n", "motor.inertia",
         "inertia: 0.9", "not both"),
    # force tables
    Case("force table going back in time", TABLE, "engagement_force: [[0 s, 0 N], [0.5 s, 0 N], [0.4 s, 3000 N]]",
         "clutch.engagement_force", "engagement_force", "time goes backwards (0.4 s after 0.5 s)"),
    Case("force table going back, block style", TABLE, "engagement_force:\n    - [0 s, 0 N]\n    - [1 s, 0 N]\n"
         "    - [500 ms, 3 kN]", "clutch.engagement_force", "- [500 ms", "row 3: time goes backwards"),
    Case("force table with a time three times", TABLE, "engagement_force: [[0 s, 0 N], [0 s, 1 N], [0 s, 2 N]]",
         "clutch.engagement_force", "engagement_force", "at most twice"),
    Case("force table with a negative force", TABLE, "engagement_force: [[0 s, 0 N], [1 s, -5 N]]",
         "clutch.engagement_force", "engagement_force", "pushed apart"),
    Case("force table before the start", TABLE, "engagement_force: [[-1 s, 0 N], [1 s, 5 N]]",
         "clutch.engagement_force", "engagement_force", "row 1"),
    Case("force table with a short row", TABLE, "engagement_force: [[0 s, 0 N], [1 s]]",
         "clutch.engagement_force", "engagement_force", "row 2: must be a pair [time, force]"),
    Case("force table with a mass", TABLE, "engagement_force: [[0 s, 0 N], [1 s, 300 kg]]",
         "clutch.engagement_force", "engagement_force", "expected a force"),
    Case("force table with times and forces swapped", TABLE, "engagement_force: [[0 N, 0 s]]",
         "clutch.engagement_force", "engagement_force", "expected a time"),
    Case("empty force table", TABLE, "engagement_force: []", "clutch.engagement_force", "engagement_force",
         "the table is empty"),
    Case("negative constant force", TABLE, "engagement_force: -3 kN", "clutch.engagement_force",
         "engagement_force", "pushed apart"),
    # malformed YAML
    # motor characteristics and flywheels
    Case("two motor characteristics", "no_load_speed: 300 rpm", "no_load_speed: 300 rpm\n  torque: 100 N*m",
         "motor.torque", "torque: 100", "give one characteristic"),
    Case("two table-like characteristics", "stall_torque: 500 N*m\n  no_load_speed: 300 rpm",
         "torque: 100 N*m\n  torque_speed: [[0 rpm, 500 N*m], [300 rpm, 0 N*m]]", "motor.torque",
         "torque: 100", "give one characteristic"),
    Case("torque-speed table with speeds not increasing", "stall_torque: 500 N*m\n  no_load_speed: 300 rpm",
         "torque_speed: [[0 rpm, 500 N*m], [200 rpm, 300 N*m], [100 rpm, 0 N*m]]", "motor.torque_speed",
         "torque_speed", "row 3: speeds must increase"),
    Case("torque-speed table of one row", "stall_torque: 500 N*m\n  no_load_speed: 300 rpm",
         "torque_speed: [[0 rpm, 500 N*m]]", "motor.torque_speed", "torque_speed", "at least two rows"),
    Case("no motor characteristic", "  stall_torque: 500 N*m\n  no_load_speed: 300 rpm\n", "",
         "motor.stall_torque", "motor:", "a characteristic"),
    # torque ripples
    Case("ripple with harmonics and a table", "  radius_of_gyration: 15 cm\n",
         "  radius_of_gyration: 15 cm\n  ripple:\n    harmonics: [{order: 3, amplitude: 100 N*m}]\n"
         "    table: [[0 deg, 0 N*m], [360 deg, 0 N*m]]\n", "motor.ripple.table", "table:", "not both"),
    Case("ripple table not spanning one period", "  radius_of_gyration: 15 cm\n",
         "  radius_of_gyration: 15 cm\n  ripple:\n    table: [[0 deg, 0 N*m], [180 deg, 50 N*m], [300 deg, 0 N*m]]\n",
         "motor.ripple.table", "table:", "must span exactly one period"),
    Case("ripple order not a whole number", "  radius_of_gyration: 15 cm\n",
         "  radius_of_gyration: 15 cm\n  ripple:\n    harmonics: [{order: 1.5, amplitude: 100 N*m}]\n",
         "motor.ripple.harmonics.0.order", "harmonics:", "whole number"),
    Case("ripple order of zero", "  radius_of_gyration: 15 cm\n",
         "  radius_of_gyration: 15 cm\n  ripple:\n    harmonics: [{order: 0, amplitude: 100 N*m}]\n",
         "motor.ripple.harmonics.0.order", "harmonics:", "at least 1"),
    Case("ripple period not positive", "  radius_of_gyration: 15 cm\n",
         "  radius_of_gyration: 15 cm\n  ripple:\n    period: 0 deg\n    harmonics: [{order: 1, amplitude: 9 N*m}]\n",
         "motor.ripple.period", "period: 0", "must be positive"),
    Case("rod not longer than the crank", None,
         "reciprocating:\n  mass: 12 kg\n  crank_radius: 8 cm\n  rod_length: 8 cm\n",
         "reciprocating.rod_length", "rod_length: 8 cm", "must be longer than the crank"),
    Case("periodic periods not a whole number", None, "periodic:\n  periods: 2.5\n", "periodic.periods",
         "periods: 2.5", "whole number"),
    Case("ripple period off every fraction of a turn", "  radius_of_gyration: 15 cm\n",
         "  radius_of_gyration: 15 cm\n  ripple:\n    period: 1 rad\n    harmonics: [{order: 1, amplitude: 9 N*m}]\n",
         "motor.ripple.period", "period: 1 rad", "exact fractions of a turn"),
    Case("rim with the inner diameter not below the outer", None,
         "flywheel:\n  density: 7200 kg/m^3\n  outer_diameter: 1 m\n  inner_diameter: 1.2 m\n  width: 10 cm\n",
         "flywheel.inner_diameter", "inner_diameter", "must be less than outer_diameter"),
    Case("rim missing its width", None,
         "flywheel:\n  density: 7200 kg/m^3\n  outer_diameter: 1 m\n  inner_diameter: 0.8 m\n",
         "flywheel.width", "flywheel:", "required"),
    Case("flywheel inertia and a rim", None, "flywheel:\n  inertia: 5 kg*m^2\n  density: 7200 kg/m^3\n",
         "flywheel.density", "density", "not both"),
    Case("flywheel on a shaft that does not exist", None, "flywheel:\n  shaft: crank\n  inertia: 5 kg*m^2\n",
         "flywheel.shaft", "shaft: crank", "'motor'"),
    Case("negative flywheel inertia", None, "flywheel:\n  inertia: -5 kg*m^2\n", "flywheel.inertia",
         "inertia: -5", "must not be negative"),
    Case("unclosed list", "mass: 500 kg", "mass: [500 kg", "load.mass", "  mass:", "malformed YAML"),
    Case("unclosed quote", "mass: 500 kg", 'mass: "500 kg', "load.mass", "  mass:", "not closed"),
    Case("tab indentation", "  mass: 500 kg", "\tmass: 500 kg", "load.mass", "\tmass:", "malformed YAML"),
    Case("duplicate key", "  mass: 500 kg", "  mass: 500 kg\n  mass: 600 kg", "load.mass", "mass: 600",
         "duplicate key (first given at line"),
    Case("duplicate section", None, "load:\n  mass: 300 kg\n", "load", "load:\n  mass: 300", "duplicate key"),
    Case("colon in a value", "mass: 500 kg", "mass: 500 kg: 3", "load.mass", "  mass:", "unexpected ':'"),
    Case("bad indentation", "  inertia: 40 kg*m^2", "    inertia: 40 kg*m^2", "drum.inertia", "    inertia",
         "malformed YAML"),
    Case("undefined alias", "mass: 500 kg", "mass: *heavy", "load.mass", "  mass:", "alias"),
    Case("two documents", None, "---\nname: other\n", "", "---", "single YAML document"),
    Case("a list, not a mapping", "*", "- motor\n- clutch\n", "", "- motor", "mapping of sections"),
    Case("a bare scalar", "*", "hoist\n", "", "hoist", "mapping of sections"),
    Case("aliases expanding without end", "*", "a: &a [x, x, x, x, x, x, x, x, x, x]\n" + "".join(
        f"a{i}: &a{i} [{', '.join([f'*a{i - 1}' if i else '*a'] * 10)}]\n" for i in range(6)), "", None,
        "more than 100000 values"),
    Case("empty file", "*", "", "", None, "empty"),
    Case("only comments", "*", "# nothing here\n", "", None, "empty"),
    # sweeps
    Case("unknown sweep key", None, "sweep:\n  clutch.engagment_force: [1000 N, 2000 N]\n",
         "sweep.clutch.engagment_force", "clutch.engagment_force", "did you mean clutch.engagement_force?"),
    Case("sweep of a section", None, "sweep:\n  clutch: [1, 2]\n", "sweep.clutch", "clutch: [", "is a section"),
    Case("sweep with a bad value", None, "sweep:\n  clutch.engagement_force: [1000 N, 2000 kg]\n",
         "sweep.clutch.engagement_force", "clutch.engagement_force: [", "value 2 (2000 kg): expected a force"),
    Case("sweep value breaking another key", None, "sweep:\n  clutch.static_friction: [0.3, 0.05]\n",
         "sweep.clutch.static_friction", "clutch.static_friction: [",
         "value 2 (0.05): clutch.kinetic_friction: must not exceed static_friction"),
    Case("sweep with no values", None, "sweep:\n  load.mass: []\n", "sweep.load.mass", "load.mass: [",
         "non-empty list"),
    Case("sweep without a list", None, "sweep:\n  load.mass: 100 kg\n", "sweep.load.mass", "load.mass: 100",
         "non-empty list"),
    Case("sweep that is not a mapping", None, "sweep: [1, 2]\n", "sweep", "sweep:", "must map keys"),
    # the rope and the ground
    Case("rope stiffness not positive", None, "rope:\n  stiffness: 0 N/m\n", "rope.stiffness", "stiffness: 0",
         "must be positive"),
    Case("rope stiffness of another kind", None, "rope:\n  stiffness: 2.5e5 N\n", "rope.stiffness",
         "stiffness: 2.5e5", "stiffness"),
    Case("rope stiffness and modulus", None, "rope:\n  stiffness: 2.5e5 N/m\n  modulus: 100 GPa\n",
         "rope.modulus", "modulus: 100", "either stiffness or a wire rope's modulus"),
    Case("wire rope without its length", None, "rope:\n  modulus: 100 GPa\n  metallic_area: 95 mm^2\n",
         "rope.free_length", "rope:", "required"),
    Case("rope damping ratio negative", None, "rope:\n  stiffness: 2.5e5 N/m\n  damping_ratio: -0.1\n",
         "rope.damping_ratio", "damping_ratio: -0.1", "must not be negative"),
    Case("rope slack negative", None, "rope:\n  stiffness: 2.5e5 N/m\n  initial_slack: -1 cm\n",
         "rope.initial_slack", "initial_slack: -1", "must not be negative"),
    Case("rope with a massless load", "mass: 500 kg", "mass: 0 kg\nrope:\n  stiffness: 2.5e5 N/m", "load.mass",
         "mass: 0 kg", "must be positive with an elastic rope"),
    Case("ground on a rigid rope with the drum turning", None,
         "ground: {}\ninitial:\n  drum_speed: 10 rpm\n", "initial.drum_speed", "drum_speed: 10", "rests on the ground"),
    Case("hoisting class unknown", None, "ground:\n  hoisting_class: HC5\n", "ground.hoisting_class",
         "hoisting_class: HC5", "HC1"),
]


@pytest.fixture(autouse=True)
def _never_simulate(monkeypatch):
    """Bad input must fail before the (slow) simulation; if a case got that far, fail loudly."""

    def refuse(*args, **kwargs):
        raise AssertionError("a bad scenario reached the simulation")

    monkeypatch.setattr(simulation, "simulate", refuse)


def _run_cli(args: list[str]):
    result = CliRunner().invoke(main, args)
    lines = result.stderr.splitlines()
    return result, lines


def _check_one_line_error(result, lines, key: str, line: int | None, words: str, source: str):
    assert result.exit_code == 2, (result.exit_code, result.output, result.exception)
    assert len(lines) == 1, lines
    message = lines[0]
    assert message.startswith("hoistsim: error: "), message
    assert "Traceback" not in result.output
    if key:
        assert f" {key}: " in message, message
    if line is not None:
        assert f"{source}:{line}: " in message, message
    else:
        assert f"{source}: " in message, message
    assert words in message, message
    assert result.stdout == ""


@pytest.mark.parametrize("case", CASES, ids=[c.id for c in CASES])
def test_bad_scenario_fails_cleanly(case, tmp_path):
    text = case.text()
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(text, encoding="utf-8")
    output = tmp_path / "out.h5"
    result, lines = _run_cli(["run", str(scenario), "-o", str(output)])
    line = line_of(text, case.at) if case.at is not None else None
    _check_one_line_error(result, lines, case.key, line, case.words, str(scenario))
    assert not output.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["scenario.yaml"]  # no temporary files either


SET_CASES = [
    # (id, --set arguments, key, words)
    ("unknown key", ["laod.mass=3 kg"], "laod", "did you mean load?"),
    ("misspelt key", ["clutch.static_frction=0.2"], "clutch.static_frction", "did you mean clutch.static_friction?"),
    ("unknown leaf", ["load.weight=3 kN"], "load.weight", "unknown key"),
    ("a section", ["clutch=3"], "clutch", "is a section"),
    ("below a value", ["load.mass.value=3"], "load.mass", "is a value, not a section"),
    ("the sweep", ["sweep.load.mass=[1 kg]"], "sweep", "cannot be given with --set"),
    ("wrong dimension", ["clutch.engagement_force=2500 kg"], "clutch.engagement_force", "expected a force"),
    ("boolean", ["clutch.static_friction=true"], "clutch.static_friction", "yes/no"),
    ("NaN", ["load.mass=.nan"], "load.mass", "finite"),
    ("NaN with a unit", ["load.mass=nan kg"], "load.mass", "finite"),
    ("negative", ["drum.diameter=-40 cm"], "drum.diameter", "must be positive"),
    ("fractional teeth", ["gears.wheel_teeth=89.5"], "gears.wheel_teeth", "whole number"),
    ("half angle of 90 deg", ["clutch.half_angle=90 deg"], "clutch.half_angle", "less than 90 deg"),
    ("kinetic above static", ["clutch.kinetic_friction=0.5"], "clutch.kinetic_friction", "static_friction"),
    ("table going back", ["clutch.engagement_force=[[1 s, 0 N], [0 s, 5 N]]"], "clutch.engagement_force",
     "time goes backwards"),
    ("no value", ["load.mass="], "load.mass", "needs a value"),
    ("decimal comma", ["clutch.static_friction=0,3"], "clutch.static_friction", "write decimals with a point, 0.3"),
    ("no equals sign", ["load.mass"], "", "expected KEY=VALUE"),
    ("the second of two", ["load.mass=600 kg", "load.mass=-1 kg"], "load.mass", "must not be negative"),
]


@pytest.mark.parametrize("args, key, words", [c[1:] for c in SET_CASES], ids=[c[0] for c in SET_CASES])
def test_bad_set_fails_cleanly(args, key, words, tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(BASE, encoding="utf-8")
    output = tmp_path / "out.h5"
    sets = [item for arg in args for item in ("--set", arg)]
    result, lines = _run_cli(["run", str(scenario), "-o", str(output), *sets])
    _check_one_line_error(result, lines, key, None, words, "--set")
    assert not output.exists()


def test_swept_key_cannot_also_be_set(tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(BASE + "sweep:\n  load.mass: [100 kg, 200 kg]\n", encoding="utf-8")
    result, lines = _run_cli(["run", str(scenario), "-o", str(tmp_path / "out.h5"), "--set", "load.mass=3 kg"])
    _check_one_line_error(result, lines, "load.mass", None, "swept", "--set")


def test_missing_scenario_file(tmp_path):
    missing = tmp_path / "nope.yaml"
    result, lines = _run_cli(["run", str(missing), "-o", str(tmp_path / "out.h5")])
    _check_one_line_error(result, lines, "", None, "no such scenario file", str(missing))
    assert list(tmp_path.iterdir()) == []


def test_scenario_that_is_not_text(tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_bytes(b"\xff\xfe\x00binary")
    result, lines = _run_cli(["run", str(scenario), "-o", str(tmp_path / "out.h5")])
    _check_one_line_error(result, lines, "", None, "UTF-8", str(scenario))


EXISTING_OUTPUT_CASES = [c for c in CASES if c.id in (
    "misspelt key", "torque for a mass", "NaN in YAML", "duplicate key", "sweep with a bad value", "empty file")]


@pytest.mark.parametrize("case", EXISTING_OUTPUT_CASES, ids=[c.id for c in EXISTING_OUTPUT_CASES])
def test_existing_output_is_left_untouched(case, tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(case.text(), encoding="utf-8")
    output = tmp_path / "out.h5"
    content = b"\x89HDF\r\n\x1a\n an earlier, good result " * 100
    output.write_bytes(content)
    os.utime(output, ns=(1_000_000_000, 1_000_000_000))
    before = output.stat()
    result, lines = _run_cli(["run", str(scenario), "-o", str(output)])
    assert result.exit_code == 2 and len(lines) == 1 and lines[0].startswith("hoistsim: error: ")
    assert output.read_bytes() == content
    assert (output.stat().st_mtime_ns, output.stat().st_ino) == (before.st_mtime_ns, before.st_ino)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["out.h5", "scenario.yaml"]


def test_existing_output_is_left_untouched_by_a_bad_set(tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(BASE, encoding="utf-8")
    output = tmp_path / "out.h5"
    output.write_bytes(b"earlier result")
    result, _ = _run_cli(["run", str(scenario), "-o", str(output), "--set", "clutch.engagement_force=2500 kg"])
    assert result.exit_code == 2
    assert output.read_bytes() == b"earlier result"


@pytest.mark.parametrize("command", [["check"], ["statics", "--json"]], ids=lambda c: c[0])
@pytest.mark.parametrize("case", [c for c in CASES if c.id in ("misspelt key", "force table going back in time")],
                         ids=lambda c: c.id)
def test_other_commands_report_the_same_error(case, command, tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(case.text(), encoding="utf-8")
    result, lines = _run_cli([*command, str(scenario)])
    _check_one_line_error(result, lines, case.key, line_of(case.text(), case.at), case.words, str(scenario))


def test_debug_shows_the_exception(tmp_path):
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(BASE.replace("mass: 500 kg", "mass: -1 kg"), encoding="utf-8")
    result = CliRunner().invoke(main, ["run", str(scenario), "-o", str(tmp_path / "o.h5"), "--debug"])
    assert result.exit_code != 0 and type(result.exception).__name__ == "ScenarioError"
    assert result.exception.key == "load.mass"


def test_real_console_script_has_no_traceback(tmp_path):
    """Once through a real process: what a user's terminal sees."""
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(BASE.replace("static_friction: 0.3", "static_friciton: 0.3"), encoding="utf-8")
    output = tmp_path / "out.h5"
    proc = subprocess.run([sys.executable, "-m", "hoistsim.cli", "run", str(scenario), "-o", str(output)],
                          capture_output=True, text=True, timeout=60, cwd=tmp_path)
    assert proc.returncode == 2, proc.stderr
    assert proc.stdout == ""
    line = line_of(scenario.read_text(), "static_friciton")
    assert proc.stderr == (f"hoistsim: error: {scenario}:{line}: clutch.static_friciton: unknown key "
                           "(did you mean clutch.static_friction?); every key: docs/scenario.md\n")
    assert not output.exists()


RIPPLE = "  ripple:\n    harmonics: [{order: 2, amplitude: 100 N*m}]\n"
FLYWHEEL_CASES = [
    # (id, options, scenario has a ripple, what the message must say)
    ("target of zero", ["--irregularity", "0"], True, "--irregularity: must be between 0 and 1"),
    ("target above one", ["--irregularity", "1.5"], True, "--irregularity: must be between 0 and 1"),
    ("target not a number", ["--irregularity", "1%"], True, "'1%' is not a valid float"),
    ("width without density", ["--irregularity", "0.01", "--width", "8 cm"], True, "need --density"),
    ("density without a size", ["--irregularity", "0.01", "--density", "7200 kg/m^3"], True,
     "--width: give either --width or --outer-diameter"),
    ("density in the wrong unit", ["--irregularity", "0.01", "--density", "7 kg", "--width", "8 cm"], True,
     "--density: expected a density"),
    ("outer diameter inside the bore", ["--irregularity", "0.01", "--density", "7200 kg/m^3", "--outer-diameter",
                                        "20 cm", "--inner-diameter", "30 cm"], True, "--outer-diameter: must exceed"),
    ("machine with nothing periodic", ["--irregularity", "0.01"], False, "motor.ripple: the machine has no periodic"),
]


@pytest.mark.parametrize("options, ripple, words", [c[1:] for c in FLYWHEEL_CASES], ids=[c[0] for c in FLYWHEEL_CASES])
def test_bad_flywheel_request_fails_cleanly(options, ripple, words, tmp_path, monkeypatch):
    monkeypatch.setattr(flywheel, "simulate_many", lambda *a, **k: pytest.fail("a bad request reached the runs"))
    text = BASE.replace("  radius_of_gyration: 15 cm\n", "  radius_of_gyration: 15 cm\n" + RIPPLE) if ripple else BASE
    scenario = tmp_path / "scenario.yaml"
    scenario.write_text(text, encoding="utf-8")
    figure = tmp_path / "delta.png"
    result, lines = _run_cli(["flywheel", str(scenario), "--plot", str(figure), *options])
    assert result.exit_code == 2, (result.exit_code, result.output, result.exception)
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error: "), lines
    assert words in lines[0], lines[0]
    assert "Traceback" not in result.output and result.stdout == ""
    assert not figure.exists()


def test_a_bare_number_on_a_speed_is_read_as_si_and_said(tmp_path, monkeypatch):
    """300 on no_load_speed is 300 rad/s (2865 rpm): accepted, SI being the rule, with one line naming the
    key, its file and line, how it was read, and how to write a unit; a number with its unit is silent."""
    monkeypatch.setattr(simulation, "simulate", lambda *a, **k: pytest.fail("check must not simulate"))
    scenario = tmp_path / "scenario.yaml"
    text = BASE.replace("no_load_speed: 300 rpm", "no_load_speed: 31.4")
    scenario.write_text(text, encoding="utf-8")
    result, lines = _run_cli(["check", str(scenario)])
    assert result.exit_code == 0, result.output
    line = line_of(text, "no_load_speed")
    assert lines == [f"hoistsim: warning: {scenario}:{line}: motor.no_load_speed: the bare number 31.4 is read as "
                     "31.4 rad/s (299.8 rpm); write the unit, like '300 rpm', to say which you mean"]
    scenario.write_text(BASE, encoding="utf-8")
    result, lines = _run_cli(["check", str(scenario)])
    assert result.exit_code == 0 and lines == []


def test_a_file_that_is_no_results_file_is_said_so_in_the_users_words(tmp_path):
    """plot and compare on an HDF5 file another program wrote, or on no HDF5 file at all: what it seems to be and
    how hoistsim writes one, one line, exit 2, nothing written; not the HDF5 library's own words."""
    import h5py

    foreign, text = tmp_path / "foreign.h5", tmp_path / "notes.h5"
    with h5py.File(foreign, "w") as f:
        f["data"] = [1.0, 2.0]
    text.write_text("notes\n", encoding="utf-8")
    for path, seems in ((foreign, "an HDF5 file whose top holds data"), (text, "it is not an HDF5 file at all")):
        for args in (["compare", str(path)], ["plot", str(path), "-o", str(tmp_path / "f.png")]):
            result = CliRunner().invoke(main, args)
            said = result.output.strip()
            assert result.exit_code == 2 and len(said.splitlines()) == 1, said
            assert f"not a hoistsim results file: {seems}" in said and "hoistsim run SCENARIO -o" in said, said
            assert "synchronously" not in said and not (tmp_path / "f.png").exists()


def test_an_empty_item_of_a_swept_list_is_named_as_the_sweeps(tmp_path):
    """`--sweep "K=3 kN,,5 kN"` names --sweep and the empty item (it was said as --set's missing value)."""
    output = tmp_path / "x.h5"
    result = CliRunner().invoke(main, ["run", str(EXERCISE6_FILE), "-o", str(output), "--sweep",
                                       "clutch.engagement_force=3 kN,,5 kN"])
    said = result.output.strip()
    assert result.exit_code == 2 and len(said.splitlines()) == 1, said
    assert said.startswith("hoistsim: error: --sweep: clutch.engagement_force: value 2 of 3 is empty"), said
    assert not output.exists()


@pytest.mark.parametrize("spec, words", [
    ("100 kg:900 kg", "load.mass: a range is FROM:TO:COUNT, and '100 kg:900 kg' has no count: give how many values, "
                      "like load.mass=100 kg:900 kg:9"),
    ("100:900 kg:5", "load.mass: range: cannot make a range from '100' to '900 kg': the ends are a pure number and "
                     "a mass; write both with their unit, like 100 kg:900 kg"),
])
def test_a_range_written_amiss_is_said_in_the_ranges_syntax(spec, words, tmp_path):
    """`--sweep "load.mass=100 kg:900 kg"` (no count) was read as one value, the product of the two ends ("a
    [mass] ** 2"); a range whose ends differ in kind was said in pint's words.  Both name the range's syntax."""
    output = tmp_path / "x.h5"
    result, lines = _run_cli(["run", str(EXERCISE6_FILE), "-o", str(output), "--sweep", f"load.mass={spec}"])
    _check_one_line_error(result, lines, "", None, words, "--sweep")
    assert "**" not in lines[0] and "[mass]" not in lines[0], lines[0]
    assert not output.exists()

"""The schema of a drivetrain drawn as shafts and couplings (``drivetrain:``), values in SI.

Shafts with their inertias and initial speeds, external torques on shafts, friction clutches between
two shafts or a shaft and ``ground`` (a brake), each torque and force a time signal (:mod:`.signals`);
gear stages that tie one shaft's speed to another's; motors on shafts (the hoist's characteristics) and
a load hanging from a shaft on a rope.
The names a user gives shafts and clutches name their outputs (``<shaft>_speed``, ``<clutch>_torque``), so
they must be plain words and must not collide.
"""

from __future__ import annotations

import math
import re
import typing

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .schema_motor import MotorSpec, RippleSpec
from .schema_load import LoadOnShaftSpec
from .schema_loss_table import LossTable
from .schema_bearing_friction import BearingFrictionSpec
from .schema_gear_groups import beyond_stage, check_gear_sides, gear_groups, given_speed, speed_key
from .schema_drawn_clutches import FrictionClutchSpec, OneWayClutchSpec
from .schema_spring import SpringSpec
from .schema_drive import (DRIVE_PARTS, DcMachineSpec, InductionMachineSpec, SpeedControllerSpec,
                           check_drive_parts)
from .schema_speed_torques import SPEED_PARTS, EddyCurrentBrakeSpec, HeatCapacitorSpec, SpeedLaws, check_speed_parts
from .schema_linkage import PlanetarySpec, check_linkages, start_speeds
from .schema_masses import LOAD, ForceSpec, MassSpec, StopsSpec, check_line_parts, line_starts
from .schema_motion_source import MotionSourceSpec
from .schema_vehicle import VehicleSpec
from .schema_shaft_parts import (SHAFT_PARTS, BrakeOnShaftSpec, OnShaft, RatchetOnShaftSpec, RotorSpec,
                                 SliderCrankSpec, check_shaft_parts)
from .signals import signal
from .units import Text

GROUND = "ground"  # the other side of a clutch that is a brake
# where a part of each kind may name the ground instead of a shaft (said where a side is no shaft)
_GROUNDED = {"clutches": "; `ground` as the second for a brake", "one_way_clutches": "",
             "bearing_frictions": "; `ground` as the second, or shaft: for friction against the ground",
             "springs": "; `ground` as the housing, first or second"}
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


class ShaftSpec(OnShaft, Section):
    """A shaft: a rigid body turning, with its inertia; its name names its outputs (``<shaft>_speed``)."""

    inertia: u.quantity(u.INERTIA, ge=0.0) = Field(description="its own (0: only with inertia tied to it)")
    speed: u.quantity(u.ANGULAR_SPEED) = Field(0.0, description="at t = 0 (a geared shaft's follows its stage)")
    angle: u.quantity(u.ANGLE) = Field(0.0, description="at t = 0 (given: <shaft>_angle is an output)")
    resisting_ripple: RippleSpec | None = Field(None, description="a torque resisting it, periodic in its angle")
    name: str = Field("", exclude=True)  # its key in drivetrain.shafts (set there, never written)

    def train(self, scenario) -> tuple:
        """(the first shaft of its gear train, its speed over that one's, its speed at the start): shafts
        geared together turn as one body."""
        drawn = scenario.drivetrain
        groups = gear_groups(drawn)
        root, ratio = groups[self.name]
        return root, ratio, start_speeds(drawn, groups)[self.name]

    def lowered(self, scenario) -> "ShaftSpec":
        """With its gear train written in (:meth:`train`: the shafts it is geared to are the drivetrain's)."""
        return self.with_resolved(train=self.train(scenario))


class TorqueSpec(SpeedLaws, Section):
    """An external torque on a shaft, named by its place (torque1, torque2, ...)."""

    shaft: Text = Field(description="the shaft it turns")
    torque: signal(u.TORQUE) | None = Field(None, description="a signal of time, in the shaft's positive sense")
    name: str = Field("", exclude=True)  # torque1, torque2, ... in the order of drivetrain.torques (set there)


_EFFICIENCY = u.quantity(u.DIMENSIONLESS, gt=0.0, le=1.0)


class MeshSpec(Section):
    """A gear mesh's losses: its efficiency when the input (the pinion) drives the output, and when the output
    drives the input (default: the same); either given, the mesh is lossy (absent: ideal)."""

    efficiency: _EFFICIENCY | None = Field(None, description="eta, where the input (the pinion) drives")
    backdrive_efficiency: _EFFICIENCY | None = Field(None, description="eta_b, where the output drives it back "
                                                     "(default: efficiency)")

    @property
    def lossy(self) -> bool:
        return self.efficiency is not None or self.backdrive_efficiency is not None

    @property
    def efficiencies(self) -> tuple[float, float]:
        """(input driving, output driving): 1 and 1 for an ideal mesh; the second defaults to the first."""
        forward = 1.0 if self.efficiency is None else self.efficiency
        return forward, forward if self.backdrive_efficiency is None else self.backdrive_efficiency


class GearStageSpec(MeshSpec):
    """A gear stage: shafts geared together turn as one body; lossy with an efficiency or a loss table.  It may join
    a shaft to a mass (its ``radius``: a pinion and its rack, a drum and its rope, a wheel rolling on the line) or
    two masses (a ``ratio``, a lever; 1: joined rigidly), ideal: the mass moves with the shaft's body, its mass m
    reaching the shaft as m r^2."""

    alternatives = (("ratio", "teeth", "radius"),)
    between: tuple[Text, Text] = Field(description="[input shaft, output shaft], or two masses, or [shaft, mass]")
    loss_table: LossTable | None = Field(None, description="Modelica's LossyGear lossTable: rows [speed, efficiency "
                                         "when the input drives, when the output drives, bearing torque when the "
                                         "input drives, when the output drives], at the input's speed")
    ratio: u.quantity(u.DIMENSIONLESS, gt=0.0) | None = Field(None, description="the input's speed over the output's")
    teeth: tuple[u.whole("teeth"), u.whole("teeth")] | None = Field(None, description="[z_in, z_out]: z_out / z_in")
    radius: u.quantity(u.LENGTH, gt=0.0) | None = Field(None, description="between [shaft, mass]: the mass moves "
                                                        "radius times the shaft's angle (a pinion and its rack, a "
                                                        "drum and its rope, a wheel rolling on the line: Modelica's "
                                                        "IdealGearR2T with ratio 1 / radius, IdealRollingWheel)")
    # a stage on a housing is a linkage of three shafts (schema_linkage)
    housing: Text | None = Field(None, description="a third shaft its housing turns with, the ratio against it (ideal)")
    name: str = Field("", exclude=True)  # its key in drivetrain.gears (set there, never written)

    def speed_ratio(self) -> float:
        """The output's speed over the input's."""
        return 1.0 / self.ratio

    def beyond(self, scenario) -> tuple:
        """The shafts on its output side: its output shaft, then every shaft geared beyond it (what presses
        its teeth)."""
        return beyond_stage(scenario.drivetrain, self.name)

    def lowered(self, scenario) -> "GearStageSpec":
        """With the shafts beyond it (:meth:`beyond`), its speed ratio and its mesh's outputs' prefix written in."""
        return self.with_resolved(beyond=self.beyond(scenario), speed_ratio=self.speed_ratio())

    @property
    def mesh(self) -> "GearStageSpec | None":
        """The lossy mesh's friction (the stage itself), or None for an ideal stage."""
        return self if self.lossy else None

    @property
    def lossy(self) -> bool:
        return super().lossy or self.loss_table is not None

    @property
    def characteristic(self) -> str:
        """Which lossy mesh: ``efficiency`` (constant efficiencies, the hoist's mesh) or ``loss_table``."""
        return "efficiency" if self.loss_table is None else "loss_table"

    @property
    def loss_key(self) -> str:
        """The key that makes it lossy, to blame where a lossy stage is refused."""
        return self.characteristic

    @model_validator(mode="after")
    def _one_ratio(self):
        if self.loss_table is not None and MeshSpec.lossy.fget(self):
            given = "efficiency" if self.efficiency is not None else "backdrive_efficiency"
            raise ScenarioError(f".{given}", "give either loss_table or efficiency (and backdrive_efficiency), not "
                                "both: constant efficiencies are the table's one row [0, efficiency, "
                                "backdrive_efficiency, 0, 0]")
        if sum(given is not None for given in (self.ratio, self.teeth, self.radius)) != 1:
            raise ScenarioError(".ratio", "give either ratio (the input's speed over the output's) or teeth "
                                "[input, output], or between a shaft and a mass its radius, one of them")
        if self.teeth is not None:
            self._derive("ratio", self.teeth[1] / self.teeth[0])
        if self.radius is not None:  # rad/s of the shaft over m/s of the mass
            self._derive("ratio", 1.0 / self.radius)
        return self


class ShaftMotorSpec(OnShaft, MotorSpec):
    """A motor on a shaft: the hoist motor's characteristics and inertia (the rotor turns with the shaft), and
    its torque's ripple, periodic in the shaft's angle."""

    shaft: Text = Field(description="the shaft its rotor turns with")
    name: str = Field("", exclude=True)  # its key in drivetrain.motors (set there, never written)


def _part_spec(field: tuple) -> tuple:
    """(a drivetrain key, the spec of each of its parts: a dict's values' or a list's items'; None otherwise)."""
    name, info = field
    args = typing.get_args(info.annotation)
    return name, (args[-1] if args and isinstance(args[-1], type) else None)


class DrivetrainSpec(Section):
    """A machine drawn as shafts and the parts on and between them; each part's key names it and its outputs."""

    shafts: dict[str, ShaftSpec] = {}
    torques: list[TorqueSpec] = []
    clutches: dict[str, FrictionClutchSpec] = {}
    one_way_clutches: dict[str, OneWayClutchSpec] = {}
    bearing_frictions: dict[str, BearingFrictionSpec] = {}
    springs: dict[str, SpringSpec] = {}
    gears: dict[str, GearStageSpec] = {}
    motors: dict[str, ShaftMotorSpec] = {}
    rotors: dict[str, RotorSpec] = {}
    slider_cranks: dict[str, SliderCrankSpec] = {}
    brakes: dict[str, BrakeOnShaftSpec] = {}
    ratchets: dict[str, RatchetOnShaftSpec] = {}
    planetaries: dict[str, PlanetarySpec] = {}
    load: LoadOnShaftSpec | None = None
    eddy_current_brakes: dict[str, EddyCurrentBrakeSpec] = {}
    heat_capacitors: dict[str, HeatCapacitorSpec] = {}
    dc_machines: dict[str, DcMachineSpec] = {}
    induction_machines: dict[str, InductionMachineSpec] = {}
    speed_controllers: dict[str, SpeedControllerSpec] = {}
    motion_sources: dict[str, MotionSourceSpec] = {}
    masses: dict[str, MassSpec] = {}
    forces: list[ForceSpec] = []
    stops: dict[str, StopsSpec] = {}
    vehicles: dict[str, VehicleSpec] = {}

    @model_validator(mode="before")
    @classmethod
    def _parts_named_by_their_keys(cls, data):
        """Each shaft, clutch, gear stage and motor knows its name, its key (a torque its place): what its
        outputs and events are called."""
        if not isinstance(data, dict):
            return data
        data = dict(data)
        for kind in ("shafts", "clutches", "one_way_clutches", "bearing_frictions", "springs", "gears", "motors",
                     *SHAFT_PARTS, *SPEED_PARTS, *DRIVE_PARTS, "planetaries", "masses", "stops",
                     "vehicles"):
            parts = data.get(kind)
            if not isinstance(parts, dict):
                continue
            named = {}
            for key, entry in parts.items():
                if isinstance(entry, dict):
                    if "name" in entry:
                        raise ScenarioError(f".{kind}.{key}.name", f"unknown key: a part of {kind} is named by its key")
                    entry = {**entry, "name": key}
                named[key] = entry
            data[kind] = named
        for kind, word in (("torques", "torque"), ("forces", "force")):
            listed = data.get(kind)
            if isinstance(listed, list):  # named by their place: torque1, torque2, ...
                for i, entry in enumerate(listed):
                    if isinstance(entry, dict) and "name" in entry:
                        raise ScenarioError(f".{kind}.{i}.name", f"unknown key: a {word} is named by its place "
                                            f"({word}1, ...)")
                data[kind] = [{**entry, "name": f"{word}{i + 1}"} if isinstance(entry, dict) else entry
                              for i, entry in enumerate(listed)]
        check_line_parts(data, {kind: spec for kind, spec in map(_part_spec, cls.model_fields.items())
                                if getattr(spec, "line_keys", None) is not None})
        return data

    @model_validator(mode="after")
    def _named_and_joined(self):
        if not self.shafts and not self.masses:
            raise ScenarioError("drivetrain.shafts", "give at least one shaft, {name: {inertia, speed}}, or mass "
                                "(drivetrain.masses: {name: {mass, position, velocity}})")
        for kind, names in (("shafts", self.shafts), ("clutches", self.clutches), ("masses", self.masses)):
            for name in names:
                if not _NAME.match(name) or name == GROUND:
                    raise ScenarioError(f"drivetrain.{kind}.{name}", "a name is a word of letters, digits and "
                                        f"underscores starting with a letter, and not {GROUND!r}")
        for kind, names in (("clutches", self.clutches), ("masses", self.masses)):
            for name in names:
                if name in self.shafts:
                    raise ScenarioError(f"drivetrain.{kind}.{name}", "is also the name of a shaft: names must "
                                        "differ (they name the outputs)")
        lines = line_starts(self)  # the masses on the line, the load among them
        if self.load is not None and LOAD in self.masses:
            raise ScenarioError(f"drivetrain.masses.{LOAD}", "is the name of the drivetrain's load, a mass on the line "
                                "parts may join already: name this mass otherwise")
        for stops in self.stops.values():
            stops.check_start(lines)
        for vehicle in self.vehicles.values():
            vehicle.check_mass(self.masses)
        for i, force in enumerate(self.forces):
            if force.mass not in lines:
                raise ScenarioError(f"drivetrain.forces.{i}.mass", f"there is no mass {force.mass!r} (masses: "
                                    f"{', '.join(lines) or 'none'})")
        known = ", ".join(self.shafts)
        for i, torque in enumerate(self.torques):
            if torque.shaft not in self.shafts:
                raise ScenarioError(f"drivetrain.torques.{i}.shaft", f"there is no shaft {torque.shaft!r} "
                                    f"(shafts: {known})")
        for kind, parts in (("clutches", self.clutches), ("one_way_clutches", self.one_way_clutches),
                            ("bearing_frictions", self.bearing_frictions), ("springs", self.springs)):
            for name, part in parts.items():
                a, b = part.sides if kind == "bearing_frictions" else part.between
                key = "shaft" if kind == "bearing_frictions" and part.between is None else "between"
                for side in (a, b):
                    grounded = side == GROUND and (side == b or kind == "springs")  # a spring's housing: either
                    massed = kind in ("springs", "clutches", "bearing_frictions") and side in lines  # on a line
                    if side not in self.shafts and not massed and not (grounded and kind != "one_way_clutches"):
                        raise ScenarioError(f"drivetrain.{kind}.{name}.{key}", f"there is no shaft {side!r} "
                                            f"(shafts: {known}{_GROUNDED[kind]})")
                if a == b:
                    raise ScenarioError(f"drivetrain.{kind}.{name}.between", f"joins shaft {a!r} to itself")
        for kind in ("clutches", "one_way_clutches"):
            for name, clutch in getattr(self, kind).items():
                on_line = any(side in lines for side in clutch.between)
                if (clutch.effective_radius is None) == (clutch.cone is None) and not on_line:
                    raise ScenarioError(f"drivetrain.{kind}.{name}.effective_radius", "give either effective_radius "
                                        "or cone (inner_radius, outer_radius, half_angle), one of them")
        self._parts_named()
        groups = gear_groups(self)
        for name, stage in self.gears.items():
            if stage.lossy:
                beyond_stage(self, name)  # a lossy stage in a loop of stages is refused there
        speeds = start_speeds(self, groups)
        self._speeds_agree(groups, speeds)
        check_shaft_parts(self, speeds)
        self._freewheels_may_start(speeds)
        self._load_may_start(speeds)
        self._every_body_has_inertia(groups)
        return self

    def _load_may_start(self, speeds):
        load = self.load
        if load is not None and load.bearings is not None and not any(
                stage.between[1] == load.shaft for stage in self.gears.values()):
            raise ScenarioError("drivetrain.load.bearings", f"are the bearings of a shaft a gear's wheel drives: "
                                f"no gear stage has shaft {load.shaft!r} (the load's) as its output")
        if load is not None and load.ground is not None and load.rope is None and speeds[load.shaft] != 0.0:
            raise ScenarioError(f"drivetrain.shafts.{load.shaft}.speed", "the load rests on the ground "
                                "(drivetrain.load.ground) on a rigid rope, so its shaft must start at rest (an "
                                "elastic rope may start slack or unloaded on a turning shaft)")

    def _freewheels_may_start(self, speeds):
        for name, clutch in self.one_way_clutches.items():
            a, b = clutch.between
            if speeds[a] > speeds[b]:
                raise ScenarioError(f"drivetrain.shafts.{a}.speed", f"starts faster ({speeds[a]:g} rad/s) than shaft "
                                    f"{b!r} ({speeds[b]:g} rad/s), which one-way clutch {name!r} lets overrun it: "
                                    f"{a!r} can never overrun {b!r}")

    def _parts_named(self):
        seen = ({name: "shafts" for name in self.shafts} | {name: "clutches" for name in self.clutches}
                | {name: "masses" for name in self.masses})
        for kind in ("one_way_clutches", "bearing_frictions", "springs", "stops", "vehicles"):
            for name, part in getattr(self, kind).items():
                # a vehicle may be named after its own mass (vehicle on vehicle: vehicle_velocity, vehicle_drag_force)
                own = kind == "vehicles" and part.mass == name and seen.get(name) == "masses"
                if not _NAME.match(name) or name == GROUND or (name in seen and not own):
                    raise ScenarioError(f"drivetrain.{kind}.{name}", "a name is a word of letters, digits and "
                                        f"underscores starting with a letter, not {GROUND!r} and not the name of "
                                        "another part (they name the outputs)")
                seen[name] = kind
        known = ", ".join(self.shafts)
        for kind, parts in (("gears", self.gears), ("motors", self.motors),
                            *((kind, getattr(self, kind)) for kind in SHAFT_PARTS)):
            for name, part in parts.items():
                # a motor or a rotor may be named after its own shaft (motor on motor: motor_speed, motor_torque)
                clash = name in seen and not (kind in ("motors", "rotors") and name == part.shaft
                                              and seen[name] == "shafts")
                if not _NAME.match(name) or name == GROUND or clash:
                    raise ScenarioError(f"drivetrain.{kind}.{name}", "a name is a word of letters, digits and "
                                        f"underscores starting with a letter, not {GROUND!r} and not the name of "
                                        "another part (they name the outputs)")
                seen[name] = kind
                if kind == "motors" and part.shaft not in self.shafts:  # the others': check_shaft_parts
                    raise ScenarioError(f"drivetrain.{kind}.{name}.shaft", f"there is no shaft {part.shaft!r} "
                                        f"(shafts: {known})")
        check_gear_sides(self)
        if self.load is not None and self.load.shaft not in self.shafts:
            raise ScenarioError("drivetrain.load.shaft", f"there is no shaft {self.load.shaft!r} (shafts: {known})")
        taken = set(seen)
        check_speed_parts(self, taken, lambda name: bool(_NAME.match(name)) and name != GROUND)
        check_drive_parts(self, taken, lambda name: bool(_NAME.match(name)) and name != GROUND)
        check_linkages(self, seen)

    def _speeds_agree(self, groups, speeds):
        for name, (root, ratio) in groups.items():
            expected, given = speeds[name], given_speed(self, name)
            units = "rad/s" if name in self.shafts else "m/s"
            if name != root and given is not None and not math.isclose(given, expected, rel_tol=1e-9,
                                                                         abs_tol=1e-12):
                raise ScenarioError(speed_key(self, name), f"is geared to {root!r}: its speed must be "
                                    f"{expected:.12g} {units} (or left out), got {given:.12g} {units}")

    def _every_body_has_inertia(self, groups):
        inertia = {root: 0.0 for root, _ in groups.values()}
        for name, (root, ratio) in groups.items():  # a mass's m reaches a shaft as m r^2
            inertia[root] += (self.shafts[name].inertia if name in self.shafts else self.masses[name].mass) * ratio**2
        for motor in self.motors.values():
            root, ratio = groups[motor.shaft]
            inertia[root] += motor.moment_of_inertia * ratio**2
        for rotor in self.rotors.values():
            root, ratio = groups[rotor.shaft]
            inertia[root] += rotor.moment_of_inertia * ratio**2
        if self.load is not None:
            root, ratio = groups[self.load.shaft]
            inertia[root] += self.load.mass * self.load.rope_radius**2 * ratio**2
        for root, total in inertia.items():
            if total <= 0.0:
                tied = [name for name, (r, _) in groups.items() if r == root]
                raise ScenarioError(f"drivetrain.shafts.{tied[0]}.inertia", "has no inertia and nothing of "
                                    f"inertia rigidly tied to it ({', '.join(tied)}): it could not be accelerated")


def hoist_only(scenario, command: str) -> None:
    """A command that answers the hoist's questions refuses a drawn drivetrain in one line."""
    if scenario.drivetrain is not None:
        raise ScenarioError("drivetrain", f"{command} answers the hoist's questions (motor, cone clutch, gears, "
                            "drum, load); this scenario draws a drivetrain", source=scenario.source)

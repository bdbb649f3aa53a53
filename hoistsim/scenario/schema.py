"""The scenario schema: one pydantic model per YAML section, values in SI.

Checks that involve one section live on its model; loading, overrides, sweeps
and the error messages are in :mod:`.loading`.
"""

from __future__ import annotations

import json
import math
from typing import Any, Literal

from pydantic import Field, PrivateAttr, model_validator

from ..errors import ScenarioError
from . import plausible
from . import units as u
from .schema_base import Section
from .schema_clutch import ConeSpec, FrictionSpec
from .schema_drivetrain import DrivetrainSpec, MeshSpec
from .schema_load import LoadSpec, buffered
from .schema_motor import MotorSpec, RippleSpec
from .schema_parts import (BearingsSpec, BrakeSpec, ClutchHeatingSpec, FlywheelSpec, RatchetSpec,
                           ReciprocatingSpec, kinetic_within_static)
from .schema_rope import BufferSpec, GroundSpec, RopeSpec
from .provenance import Provenance
from .tables import EngagementForce
from .units import FreeText, Text
from .yamlsource import copy_plain

SOLVERS = ("tsit5", "dopri5", "dopri8", "bosh3", "heun", "kvaerno3", "kvaerno5")


# --------------------------------------------------------------------------------------
# the schema: one model per section


class ClutchSpec(FrictionSpec, ConeSpec):
    """The hoist's cone clutch: a cone's faces and their friction (the keys a drawn clutch has too), pressed by
    an engagement force that is a table of time, with its halves' inertias on the motor and pinion shafts."""

    engagement_force: EngagementForce = Field(description="the axial force pressing the cone: a constant, or a "
                                              "table of time (a repeated time a step; held beyond its ends)")
    driving_inertia: u.quantity(u.INERTIA, ge=0.0) = Field(0.0, description="the clutch half on the motor shaft")
    driven_inertia: u.quantity(u.INERTIA, ge=0.0) = Field(0.0, description="the clutch half on the pinion shaft")


class GearSpec(MeshSpec):
    """The hoist's spur gears: pinion 1 on the clutch's output shaft, wheel 2 on the drum shaft, and the mesh's
    losses (the keys a drawn gear stage has too, schema_drivetrain's MeshSpec; absent: ideal, as in exercise 6)."""

    pinion_teeth: u.whole("teeth") = Field(description="z1, the pinion's on the clutch's output shaft")
    wheel_teeth: u.whole("teeth") = Field(description="z2, the wheel's on the drum shaft (ratio z2 / z1)")
    module: u.quantity(u.LENGTH, plausible=plausible.GEAR_MODULE, gt=0.0) = Field(
        description="m: the pitch diameters are m z1 and m z2")
    pressure_angle: u.quantity(u.ANGLE, gt=0.0, lt=math.pi / 2) = Field(math.radians(20.0), description=(
        "of the teeth: the tooth force's radial part (the bearings' loads)"))
    pinion_inertia: u.quantity(u.INERTIA, ge=0.0) = Field(0.0, description="the pinion's, on its shaft")
    wheel_inertia: u.quantity(u.INERTIA, ge=0.0) = Field(0.0, description="the wheel's, on the drum shaft")

    @property
    def characteristic(self) -> str:
        """Which variant: ``ideal`` (power passes unchanged) or ``lossy`` (an efficiency either way)."""
        return "lossy" if self.lossy else "ideal"

    @property
    def mesh(self) -> "GearSpec | None":
        """The lossy mesh's friction (the same keys), or None for an ideal mesh."""
        return self if self.lossy else None


class DrumSpec(Section):
    """The rope drum on the wheel's shaft: the rope winds at half its diameter."""

    diameter: u.quantity(u.LENGTH, plausible=plausible.HOIST_DRUM_DIAMETER, gt=0.0) = Field(
        description="where the rope winds (the load's lever: half of it)")
    inertia: u.quantity(u.INERTIA, gt=0.0) = Field(description="the drum's own, on its shaft")
    resisting_ripple: RippleSpec | None = Field(None, description="a torque resisting the lift, periodic in the "
                                                "drum angle")


class InitialSpec(Section):
    """How the hoist starts: its shafts' speeds at t = 0 (default: at rest)."""

    alternatives = (("steady_lift", "motor_speed + drum_speed"),)
    motor_speed: u.quantity(u.ANGULAR_SPEED) = Field(0.0, description="the motor shaft's at t = 0")
    drum_speed: u.quantity(u.ANGULAR_SPEED) = Field(0.0, description="the drum shaft's at t = 0 (0 with a brake)")
    # Start already lifting at the steady locked speed, where the motor torque
    # equals the load torque: the constant-speed condition of the exercise.
    steady_lift: bool = Field(False, description="start lifting, clutch locked, at the speed where the motor's "
                              "torque equals the load's")

    @model_validator(mode="after")
    def _one_way_to_start(self):
        if self.steady_lift and "motor_speed" in self.model_fields_set:
            raise ScenarioError("initial.motor_speed", "give either steady_lift: true or the speeds, not both")
        if self.steady_lift and "drum_speed" in self.model_fields_set:
            raise ScenarioError("initial.drum_speed", "give either steady_lift: true or the speeds, not both")
        return self




class PeriodicSpec(Section):
    """The periodic regime's analysis (implied by a ripple or a slider-crank)."""

    periods: u.whole("periods") = Field(5, description="analysed once the regime has settled")






# The finest relative tolerance a float64 run can honour, some 45 times float64's resolution (2.2e-16):
# below it round-off, not the tolerance, sets the steps.  Measured on exercise 6 (0.5 s, atol 1e-20):
# rtol 1e-12, 1e-14, 1e-16, 1e-18, 1e-20 took 176, 435, 1086, 3203, 75581 steps (0, 0, 1, 272, 21213 of
# them rejected) for an energy ledger closing to 5.6e-14, 6.7e-16, 4.0e-16, 1.1e-15, 1.3e-14: finer than
# 1e-14 buys steps, not accuracy.
RTOL_FLOOR = 1e-14


class SimulationSpec(Section):
    """How long to run, how often to write a row, and the integration's tolerances."""

    duration: u.quantity(u.TIME, gt=0.0) = Field(description="the run, from t = 0")
    output_interval: u.quantity(u.TIME, gt=0.0) = Field(description="output rows at these times, plus every event's")
    rtol: u.quantity(u.DIMENSIONLESS, ge=RTOL_FLOOR, lt=1.0) = Field(
        1e-8, description=f"the steps' relative tolerance; at least {RTOL_FLOOR:g}, the finest a float64 run honours "
                          "(finer, its round-off outweighs the tolerance: more steps, no more accuracy)")
    atol: u.quantity(u.DIMENSIONLESS, gt=0.0) = Field(1e-10, description="the steps' absolute tolerance")
    solver: Literal[SOLVERS] = Field("tsit5", description="diffrax's solver")  # type: ignore[valid-type]
    max_switches: u.whole("mode switches") = Field(200, description="more mode switches than this: the run is "
                                                   "reported as chattering (a new value compiles nothing)")

    @model_validator(mode="after")
    def _grid(self):
        if self.output_interval > self.duration:
            raise ScenarioError("simulation.output_interval", f"must not exceed the duration "
                                f"({self.duration:g} s), got {self.output_interval:g} s")
        if self.duration / self.output_interval > 2_000_000:
            raise ScenarioError("simulation.output_interval", f"gives {self.duration / self.output_interval:.3g} "
                                "output rows; at most 2e6 are allowed")
        return self


class Scenario(Section):
    """One YAML file: the hoist by its sections, or a machine drawn as a drivetrain; the run; a sweep."""

    alternatives = (("motor + clutch + gears + drum + load", "drivetrain"),)
    name: Text = Field(description="labels the outputs")
    description: FreeText = Field("", description="free text")
    # the hoist's sections, or (instead of them, never with them) a drivetrain drawn as shafts and clutches
    motor: MotorSpec | None = Field(None, description="the hoist's motor (required without drivetrain)")
    clutch: ClutchSpec | None = Field(None, description="the hoist's cone clutch (required without drivetrain)")
    gears: GearSpec | None = Field(None, description="the hoist's spur gears (required without drivetrain)")
    drum: DrumSpec | None = Field(None, description="the hoist's drum (required without drivetrain)")
    load: LoadSpec | None = Field(None, description="the hoist's load (required without drivetrain)")
    drivetrain: DrivetrainSpec | None = Field(None, description="a machine drawn as shafts and parts, instead of "
                                              "the hoist's sections")
    gravity: u.quantity(u.ACCELERATION, ge=0.0) = Field(9.81, description="g, on the load")
    initial: InitialSpec = Field(InitialSpec(), description="the hoist's speeds at t = 0")
    flywheel: FlywheelSpec | None = Field(None, description="a flywheel on the motor or drum shaft")
    reciprocating: ReciprocatingSpec | None = Field(None, description="a slider-crank on the motor shaft")
    periodic: PeriodicSpec | None = Field(None, description="the periodic regime's analysis")
    brake: BrakeSpec | None = Field(None, description="a brake holding the drum until its release")
    ratchet: RatchetSpec | None = Field(None, description="a pawl on the drum shaft: it turns to lift only")
    clutch_heating: ClutchHeatingSpec | None = Field(None, description="the clutch faces' temperature, and "
                                                     "their friction against it")
    bearings: BearingsSpec | None = Field(None, description="the drum shaft's bearing loads in time")
    rope: RopeSpec | None = Field(None, description="an elastic rope: the load a body of its own")
    ground: GroundSpec | None = Field(None, description="the load starts resting on the ground")
    buffer: BufferSpec | None = Field(None, description="a buffer under the load at the end of its travel (with "
                                      "rope:)")
    simulation: SimulationSpec = Field(description="the run's length, output rows and tolerances")
    sweep: dict[str, Any] | None = Field(None, description="one run per value of the keys it names (two keys: "
                                         "every combination)")  # checked by check_sweep

    _provenance: Provenance = PrivateAttr(default_factory=Provenance)  # given by with_provenance only

    @property
    def provenance(self) -> Provenance:
        """What loading learned of this scenario: its text and source, its plain data, its sweep."""
        return self._provenance

    def with_provenance(self, provenance: Provenance) -> Scenario:
        """This scenario (a copy) with what loading learned of it."""
        copied = self.model_copy()
        copied._provenance = provenance
        return copied

    @property
    def warnings(self) -> list[str]:
        """One line each: values accepted that may not say what was meant (a bare number on a speed)."""
        return list(self._provenance.warnings)

    @model_validator(mode="after")
    def _a_hoist_or_a_drivetrain(self):
        hoist = ("motor", "clutch", "gears", "drum", "load")
        if self.drivetrain is None:
            for name in hoist:
                if getattr(self, name) is None:
                    raise ScenarioError(name, "required section is missing")
            return self
        for name in (*hoist, "flywheel", "reciprocating", "periodic", "brake", "ratchet", "clutch_heating",
                     "bearings", "rope", "ground", "buffer"):
            if getattr(self, name) is not None:
                raise ScenarioError(name, "cannot be given with drivetrain: (a scenario draws the hoist by its "
                                    "sections or a machine as a drivetrain, not both)")
        return self

    @model_validator(mode="after")
    def _brake_holds_still_drum(self):
        holding = self.brake is not None and self.brake.characteristic == "holding"
        if holding and self.initial.drum_speed != 0.0:
            raise ScenarioError("initial.drum_speed", "must be 0 when a holding brake (brake: without "
                                "static_torque) keeps the drum still at the start")
        if holding and self.initial.steady_lift:
            raise ScenarioError("initial.steady_lift", "a steady lift cannot start with the brake holding the drum")
        return self

    @model_validator(mode="after")
    def _pawl_on_a_lowering_drum(self):
        if self.ratchet is not None and self.initial.drum_speed < 0.0:
            raise ScenarioError("initial.drum_speed", "must not be negative with a ratchet: the pawl would stop "
                                "a lowering drum dead")
        return self

    @model_validator(mode="after")
    def _load_on_the_rope(self):
        if self.rope is not None and self.load.mass <= 0.0:
            raise ScenarioError("load.mass", "must be positive with an elastic rope (rope:): the load is a body "
                                "of its own on it")
        buffered(self.buffer, self.rope, self.ground, "")
        if self.ground is not None and self.rope is None and (self.initial.drum_speed != 0.0
                                                               or self.initial.steady_lift):
            key = "initial.steady_lift" if self.initial.steady_lift else "initial.drum_speed"
            raise ScenarioError(key, "the load rests on the ground (ground:) on a rigid rope, so the drum must "
                                "start at rest (an elastic rope, rope:, may start slack or unloaded on a turning drum)")
        return self

    @model_validator(mode="after")
    def _kinetic_within_static_when_hot(self):
        if self.clutch_heating is not None:
            kinetic_within_static(self.clutch_heating, self.clutch.static_friction, self.clutch.kinetic_friction,
                                  "clutch_heating")
        return self

    @model_validator(mode="after")
    def _periodic_parts_repeat(self):
        if self.periodic_regime is not None:
            from .period import machine_period_turns

            machine_period_turns(self)  # periods must be exact fractions of a turn (a one-line error if not)
        return self

    @property
    def periodic_regime(self) -> PeriodicSpec | None:
        """How to report the periodic regime: ``periodic:`` as given, its defaults where an element
        makes the machine periodic (a ripple, a slider-crank), None for a machine that is not."""
        if self.periodic is not None:
            return self.periodic
        if self.drivetrain is not None:
            return None
        periodic = (self.motor.ripple, self.drum.resisting_ripple, self.reciprocating)
        return PeriodicSpec() if any(part is not None for part in periodic) else None

    @property
    def text(self) -> str:
        """The scenario as read, with command-line overrides noted."""
        return self._provenance.text

    @property
    def source(self) -> str:
        return self._provenance.source

    @property
    def raw(self) -> dict:
        """The scenario as plain data (before unit conversion), overrides applied."""
        return copy_plain(self._provenance.raw)

    def resolved(self) -> dict:
        """The scenario in SI numbers, as JSON-friendly data."""
        return json.loads(self.model_dump_json(exclude={"sweep"}))

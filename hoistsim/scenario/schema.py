"""The scenario schema: one pydantic model per YAML section, values in SI.

Checks that involve one section live on its model; loading, overrides, sweeps
and the error messages are in :mod:`.loading`.
"""

from __future__ import annotations

import json
import math
from typing import Any, Literal

from pydantic import PrivateAttr, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .schema_clutch import ConeSpec, FrictionSpec
from .schema_drivetrain import DrivetrainSpec, MeshSpec
from .schema_load import LoadSpec
from .schema_motor import MotorSpec, RippleSpec
from .schema_parts import (BearingsSpec, BrakeSpec, ClutchHeatingSpec, FlywheelSpec, RatchetSpec,
                           ReciprocatingSpec, kinetic_within_static)
from .schema_rope import GroundSpec, RopeSpec
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

    engagement_force: EngagementForce
    driving_inertia: u.quantity(u.INERTIA, ge=0.0) = 0.0  # clutch half on the motor shaft
    driven_inertia: u.quantity(u.INERTIA, ge=0.0) = 0.0  # clutch half on the pinion shaft


class GearSpec(MeshSpec):
    """The hoist's spur gears: pinion 1 on the clutch's output shaft, wheel 2 on the drum shaft, and the mesh's
    losses (:class:`.schema_drivetrain.MeshSpec`, the keys a drawn gear stage has too; absent: ideal, as in
    exercise 6)."""

    pinion_teeth: u.whole("teeth")
    wheel_teeth: u.whole("teeth")
    module: u.quantity(u.LENGTH, gt=0.0)
    pressure_angle: u.quantity(u.ANGLE, gt=0.0, lt=math.pi / 2) = math.radians(20.0)
    pinion_inertia: u.quantity(u.INERTIA, ge=0.0) = 0.0
    wheel_inertia: u.quantity(u.INERTIA, ge=0.0) = 0.0

    @property
    def characteristic(self) -> str:
        """Which variant: ``ideal`` (power passes unchanged) or ``lossy`` (an efficiency either way)."""
        return "lossy" if self.lossy else "ideal"

    @property
    def mesh(self) -> "GearSpec | None":
        """The lossy mesh's friction (the same keys), or None for an ideal mesh."""
        return self if self.lossy else None


class DrumSpec(Section):
    diameter: u.quantity(u.LENGTH, gt=0.0)
    inertia: u.quantity(u.INERTIA, gt=0.0)
    resisting_ripple: RippleSpec | None = None  # a torque resisting the lift, periodic in the drum angle


class InitialSpec(Section):
    motor_speed: u.quantity(u.ANGULAR_SPEED) = 0.0
    drum_speed: u.quantity(u.ANGULAR_SPEED) = 0.0
    # Start already lifting at the steady locked speed, where the motor torque
    # equals the load torque: the constant-speed condition of the exercise.
    steady_lift: bool = False

    @model_validator(mode="after")
    def _one_way_to_start(self):
        if self.steady_lift and "motor_speed" in self.model_fields_set:
            raise ScenarioError("initial.motor_speed", "give either steady_lift: true or the speeds, not both")
        if self.steady_lift and "drum_speed" in self.model_fields_set:
            raise ScenarioError("initial.drum_speed", "give either steady_lift: true or the speeds, not both")
        return self




class PeriodicSpec(Section):
    periods: u.whole("periods") = 5  # analysed once the regime has settled






class SimulationSpec(Section):
    duration: u.quantity(u.TIME, gt=0.0)
    output_interval: u.quantity(u.TIME, gt=0.0)
    rtol: u.quantity(u.DIMENSIONLESS, gt=0.0, lt=1.0) = 1e-8
    atol: u.quantity(u.DIMENSIONLESS, gt=0.0) = 1e-10
    solver: Literal[SOLVERS] = "tsit5"  # type: ignore[valid-type]
    max_switches: u.whole("mode switches") = 200  # before a run is declared chattering

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
    name: Text
    description: FreeText = ""
    # the hoist's sections, or (instead of them, never with them) a drivetrain drawn as shafts and clutches
    motor: MotorSpec | None = None
    clutch: ClutchSpec | None = None
    gears: GearSpec | None = None
    drum: DrumSpec | None = None
    load: LoadSpec | None = None
    drivetrain: DrivetrainSpec | None = None
    gravity: u.quantity(u.ACCELERATION, ge=0.0) = 9.81
    initial: InitialSpec = InitialSpec()
    flywheel: FlywheelSpec | None = None
    reciprocating: ReciprocatingSpec | None = None
    periodic: PeriodicSpec | None = None
    brake: BrakeSpec | None = None
    ratchet: RatchetSpec | None = None
    clutch_heating: ClutchHeatingSpec | None = None
    bearings: BearingsSpec | None = None
    rope: RopeSpec | None = None
    ground: GroundSpec | None = None
    simulation: SimulationSpec
    sweep: dict[str, Any] | None = None  # checked by check_sweep

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
                     "bearings", "rope", "ground"):
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

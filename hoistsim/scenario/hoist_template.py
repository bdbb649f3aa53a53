"""The hoist's sections written out as a drawn drivetrain's parts: the machine is built from those.

The hoist's keys are read and checked as they are (:mod:`.schema`); a part the template draws is then the
drawn drivetrain's part of its kind, on the template's shafts (``motor``, ``pinion``, ``drum``), with what the
hoist's part has beside (a clutch's halves' inertias, its friction against temperature) and its outputs
under the names the hoist's users know (``slip_speed``, ``engagement_force``, ``lockup_time``, ...).  Made
from values checked already (no validation again: a sweep's values may be a column of runs).
"""

from __future__ import annotations

import numpy as np

from .schema_clutch import ConeSpec
from .schema import FlywheelSpec
from .schema_drivetrain import FrictionClutchSpec, GearStageSpec, LoadOnShaftSpec, ShaftMotorSpec, ShaftSpec
from .signals import TimeSignal

# The cone clutch's outputs by their role, as the hoist names them (a drawn clutch's are <name>_<role>).
CLUTCH_NAMES = {"torque": "clutch_torque", "slip": "slip_speed", "locked": "clutch_locked", "force": "engagement_force",
                "energy": "clutch_energy", "capacity": "clutch_capacity", "mode": "clutch_mode",
                "lockup_time": "lockup_time", "slip_duration": "slip_duration", "peak_torque": "peak_clutch_torque",
                "peak_slip_speed": "peak_slip_speed", "slip_energy": "slip_energy"}


class TemplateShaftSpec(ShaftSpec):
    """A shaft the hoist's template draws (motor, pinion, drum): geared where the template says, its speed
    an output where the hoist's was, and its speed at the start no speed scale of the machine (the hoist's
    slip resolution has always come from its motor's speeds, or failing that all its bodies')."""

    geared_to: str = ""  # the shaft it turns with, "" for a body
    ratio_to_root: float = 1.0  # its speed over that shaft's
    speed_observed: bool = True

    def train(self, scenario) -> tuple:
        return self.geared_to or self.name, self.ratio_to_root, self.speed * self.ratio_to_root

    def sets_speed_scale(self) -> bool:
        return False

    def observed(self) -> bool:
        return self.speed_observed


def motor_shaft_as_drawn(spec, scenario) -> TemplateShaftSpec:
    """The motor shaft: a body turning at ``initial.motor_speed``, its inertia the motor's rotor's (and what
    else the scene keys to it)."""
    return TemplateShaftSpec.model_construct(name="motor", inertia=0.0, speed=scenario.initial.motor_speed)


def pinion_shaft_as_drawn(spec, scenario) -> TemplateShaftSpec:
    """The pinion shaft (the clutch's output): a body with the pinion's inertia, turning z2/z1 times as fast as
    the drum at ``initial.drum_speed``; its speed is no output of the hoist (the motor's less the slip)."""
    return TemplateShaftSpec.model_construct(
        name="pinion", inertia=spec.pinion_inertia,
        speed=scenario.initial.drum_speed * spec.wheel_teeth / spec.pinion_teeth, speed_observed=False)


def drum_shaft_as_drawn(spec, scenario) -> TemplateShaftSpec:
    """The drum shaft, geared to the pinion by the gears' teeth (z1/z2 times its speed), with the wheel's
    inertia (the drum's own is the drum's: :func:`drum_as_drawn`)."""
    ratio = float(spec.pinion_teeth) / float(spec.wheel_teeth)
    return TemplateShaftSpec.model_construct(name="drum", inertia=spec.wheel_inertia, speed=scenario.initial.drum_speed,
                                             geared_to="pinion", ratio_to_root=ratio)


class TemplateRotorSpec(FlywheelSpec):
    """The drum's own inertia as the template keys it to the drum shaft: a rotor named drum."""

    def part_name(self) -> str:
        return "drum"


def drum_as_drawn(spec, scenario) -> TemplateRotorSpec:
    """The drum's inertia: a rotor keyed to the drum shaft (its diameter is the load's rope radius)."""
    return TemplateRotorSpec.model_construct(shaft="drum", inertia=spec.inertia)


class TemplateStageSpec(GearStageSpec):
    """The hoist's gears as the template draws their lossy mesh: the stage from the pinion to the drum, its
    speed ratio z1/z2 from the teeth, its outputs ``mesh_torque``, ``mesh_mode``, ..."""

    def speed_ratio(self) -> float:
        return float(self.teeth[0]) / float(self.teeth[1])

    def mesh_prefix(self) -> str:
        return "mesh"

    def beyond(self, scenario) -> tuple:
        return ("drum",)


def mesh_as_drawn(spec, scenario) -> TemplateStageSpec:
    """The hoist's lossy mesh (``gears:`` with an efficiency) as the drivetrain's stage ``mesh``."""
    return TemplateStageSpec.model_construct(
        name="mesh", between=("pinion", "drum"), teeth=(spec.pinion_teeth, spec.wheel_teeth),
        ratio=spec.wheel_teeth / spec.pinion_teeth, efficiency=spec.efficiency,
        backdrive_efficiency=spec.backdrive_efficiency)


def motor_as_drawn(spec, scenario) -> ShaftMotorSpec:
    """The hoist's ``motor:`` as the drivetrain's motor ``motor`` on the motor shaft (outputs motor_torque,
    motor_work)."""
    return ShaftMotorSpec.model_construct(**{name: getattr(spec, name) for name in type(spec).model_fields},
                                          shaft="motor", name="motor")


def load_as_drawn(spec, scenario) -> LoadOnShaftSpec:
    """The hoist's ``load:`` on a rigid rope as the drivetrain's load, hanging from the drum shaft at half
    the drum's diameter."""
    return LoadOnShaftSpec.model_construct(mass=spec.mass, shaft="drum", rope_radius=0.5 * scenario.drum.diameter)


class TemplateClutchSpec(FrictionClutchSpec):
    """The hoist's cone clutch as the template draws it: a friction clutch from the motor shaft to the pinion
    shaft, pressed by the engagement force, with its halves' inertias, its friction against the faces'
    temperature where ``clutch_heating`` gives tables, and the hoist's names for its outputs."""

    driving_inertia: float = 0.0
    driven_inertia: float = 0.0
    friction_fade: dict | None = None

    def halves(self) -> tuple[float, float]:
        return self.driving_inertia, self.driven_inertia

    def fade(self) -> dict | None:
        return self.friction_fade

    def output_names(self) -> dict[str, str]:
        return CLUTCH_NAMES


def clutch_as_drawn(spec, scenario) -> TemplateClutchSpec:
    """The hoist's ``clutch:`` (and ``clutch_heating:``'s friction tables) as the drivetrain's clutch ``clutch``."""
    table = spec.engagement_force
    heating = scenario.clutch_heating
    cone = ConeSpec.model_construct(inner_radius=spec.inner_radius, outer_radius=spec.outer_radius,
                                    half_angle=spec.half_angle, mean_radius=spec.mean_radius)
    force = TimeSignal.model_construct(times=table.times, values=table.forces, amplitudes=(), frequencies=(),
                                       phases=())
    return TemplateClutchSpec.model_construct(
        name="clutch", between=("motor", "pinion"), static_friction=spec.static_friction,
        kinetic_friction=spec.kinetic_friction, surfaces=spec.surfaces, effective_radius=None, cone=cone, force=force,
        driving_inertia=spec.driving_inertia, driven_inertia=spec.driven_inertia,
        friction_fade=fade_tables(heating, spec) if heating is not None and heating.fades else None)


def fade_tables(heating, spec) -> dict:
    """The clutch's friction against temperature: clutch_heating's tables (a table not given is the clutch's
    constant), both on the knots of either, which leaves each unchanged (linear between)."""
    given = [table for table in (heating.static_friction, heating.kinetic_friction) if table is not None]
    knots = np.asarray(sorted({row[0] for table in given for row in table}), float)

    def on_knots(table, constant):
        if table is None:
            return np.full(knots.shape, float(constant))
        temperatures, values = (np.asarray(column, float) for column in zip(*table))
        return np.interp(knots, temperatures, values)

    return {"temperatures": knots, "static": on_knots(heating.static_friction, spec.static_friction),
            "kinetic": on_knots(heating.kinetic_friction, spec.kinetic_friction)}

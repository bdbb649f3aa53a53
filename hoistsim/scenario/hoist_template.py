"""The hoist's sections written out as a drawn drivetrain's parts: the machine is built from those.

The hoist's keys are read and checked as they are (:mod:`.schema`); each section is then the drawn
drivetrain's part of its kind (:data:`TEMPLATE`), on the template's shafts (``motor``, ``pinion``, ``drum``),
with what the hoist's part has beside (a clutch's halves' inertias); and the names the hoist's users know its
outputs by (``slip_speed``, ``lockup_time``, ``ripple_torque``, ...), applied where its results are written (the
machine runs under the drawn parts' own).  Made from values checked already (no validation again: a sweep's
values may be a column of runs).
"""

from __future__ import annotations

from typing import NamedTuple

from .period import machine_period
from .schema import PeriodicSpec
from .schema_clutch import ConeSpec
from .schema_drawn_clutches import FrictionClutchSpec
from .schema_drivetrain import GearStageSpec, ShaftMotorSpec, ShaftSpec
from .schema_load import LoadBearingsSpec, LoadOnShaftSpec
from .schema_shaft_parts import (
    BrakeOnShaftSpec,
    RatchetOnShaftSpec,
    RotorSpec,
    SliderCrankSpec,
)
from .signals import TimeSignal

# The drawn parts' outputs the hoist names otherwise (its users' names, kept in its files), drawn name -> the
# hoist's; None: an output the hoist does not write (its pinion's speed: the motor's less the slip).
CLUTCH_NAMES = {"clutch_slip": "slip_speed", "clutch_force": "engagement_force", "clutch_lockup_time": "lockup_time",
                "clutch_slip_duration": "slip_duration", "clutch_peak_torque": "peak_clutch_torque",
                "clutch_peak_slip_speed": "peak_slip_speed", "clutch_slip_energy": "slip_energy"}
HEATING_NAMES = {"clutch_temperature_peak": "temperature_peak", "clutch_overheat_time": "overheat_time",
                 "clutch_overheat": "overheat"}
PINION_NAMES = {"pinion_speed": None, "final_pinion_speed": None}
# the hoist's lossy mesh is the stage "mesh": its outputs <stage>_mesh_<what> are the hoist's mesh_<what>
MESH_NAMES = {f"mesh_mesh_{what}": f"mesh_{what}" for what in ("torque", "loss_power", "heat", "mode", "loss_energy")}
MOTOR_RIPPLE_NAMES = {"motor_ripple_torque": "ripple_torque"}
DRUM_RIPPLE_NAMES = {"drum_resisting_ripple_torque": "resisting_ripple_torque",
                     "drum_resisting_ripple_work": "resisting_ripple_work"}
SLIDER_CRANK_NAMES = {"reciprocating_position": "slider_position"}


def section_of(scenario, parts: tuple):
    """What a dotted section's parts name within the scenario (a section within a section: motor.ripple),
    None where it is absent."""
    holder = scenario
    for part in parts:  # a scenario, or its resolved values read back from a results file (dicts)
        holder = holder.get(part) if isinstance(holder, dict) else getattr(holder, part, None)
        if holder is None:
            return None
    return holder


class TemplatePart(NamedTuple):
    """A drawn part a hoist section stands for: its path in a drivetrain (``drivetrain.shafts.*``), what writes
    it out from the section and the scenario, and the hoist's names for its outputs (applied when results are
    written: the machine runs under the drawn names)."""

    path: str
    as_drawn: object  # (section, scenario) -> the drawn part's spec (for a key within a part: the part)
    names: dict = {}  # a drawn output's name -> the hoist's (None: not written)
    name: str = ""  # the drawn part's name, where it is a whole part of a kind (drivetrain.<kind>.*)


def _shaft(name: str, inertia: float, speed: float, geared_to: str = "", ratio: float = 1.0) -> ShaftSpec:
    """A shaft the template draws, with its gear train written in (turning with ``geared_to`` at ``ratio`` times
    its speed, or a body of its own)."""
    return ShaftSpec.model_construct(name=name, inertia=inertia, speed=speed).with_resolved(
        train=(geared_to or name, ratio, speed * ratio))


def motor_shaft_as_drawn(spec, scenario) -> ShaftSpec:
    """The motor shaft: a body turning at ``initial.motor_speed``, its inertia the motor's rotor's (and what
    else the scene keys to it)."""
    return _shaft("motor", 0.0, scenario.initial.motor_speed)


def pinion_shaft_as_drawn(spec, scenario) -> ShaftSpec:
    """The pinion shaft (the clutch's output): a body with the pinion's inertia, turning z2/z1 times as fast as
    the drum at ``initial.drum_speed``; its speed is no output of the hoist (the motor's less the slip)."""
    return _shaft("pinion", spec.pinion_inertia, scenario.initial.drum_speed * spec.wheel_teeth / spec.pinion_teeth)


def drum_shaft_as_drawn(spec, scenario) -> ShaftSpec:
    """The drum shaft, geared to the pinion by the gears' teeth (z1/z2 times its speed), with the wheel's
    inertia (the drum's own is the drum's: :func:`drum_as_drawn`)."""
    ratio = float(spec.pinion_teeth) / float(spec.wheel_teeth)
    return _shaft("drum", spec.wheel_inertia, scenario.initial.drum_speed, geared_to="pinion", ratio=ratio)


def drum_ripple_as_drawn(spec, scenario) -> ShaftSpec:
    """The drum's resisting ripple: the drum shaft's (outputs resisting_ripple_torque, resisting_ripple_work)."""
    return ShaftSpec.model_construct(name="drum", resisting_ripple=spec)


def drum_as_drawn(spec, scenario) -> RotorSpec:
    """The drum's inertia: a rotor named drum keyed to the drum shaft (its diameter is the load's rope's)."""
    return RotorSpec.model_construct(name="drum", shaft="drum", inertia=spec.inertia)


def flywheel_as_drawn(spec, scenario) -> RotorSpec:
    """The flywheel: a rotor keyed to the motor or the drum shaft."""
    return RotorSpec.model_construct(name="flywheel", shaft=spec.shaft, inertia=spec.moment_of_inertia)


def mesh_as_drawn(spec, scenario) -> GearStageSpec:
    """The hoist's lossy mesh (``gears:`` with an efficiency) as the drivetrain's stage ``mesh`` from the pinion
    to the drum: its speed ratio z1/z2 from the teeth, its outputs ``mesh_torque``, ``mesh_mode``, ..."""
    return GearStageSpec.model_construct(
        name="mesh", between=("pinion", "drum"), teeth=(spec.pinion_teeth, spec.wheel_teeth),
        ratio=spec.wheel_teeth / spec.pinion_teeth, efficiency=spec.efficiency,
        backdrive_efficiency=spec.backdrive_efficiency,
    ).with_resolved(beyond=("drum",), speed_ratio=float(spec.pinion_teeth) / float(spec.wheel_teeth))


def motor_as_drawn(spec, scenario) -> ShaftMotorSpec:
    """The hoist's ``motor:`` as the drivetrain's motor ``motor`` on the motor shaft (outputs motor_torque,
    motor_work; its ripple's ripple_torque, motor_ripple_work)."""
    drawn = ShaftMotorSpec.model_construct(**{name: getattr(spec, name) for name in type(spec).model_fields},
                                           shaft="motor", name="motor")
    drawn._derived = spec.derived()  # a stall torque from the nameplate stays the nameplate's to say
    return drawn


def motor_ripple_as_drawn(spec, scenario) -> ShaftMotorSpec:
    """The motor's ripple: the drawn motor's, which holds it."""
    return motor_as_drawn(scenario.motor, scenario)


def load_as_drawn(spec, scenario) -> LoadOnShaftSpec:
    """The hoist's ``load:`` (with ``rope:``, ``ground:`` and the drum shaft's ``bearings:``) as the drivetrain's
    load, hanging from the drum shaft at half the drum's diameter, the drum turning at ``initial.drum_speed`` at
    the start."""
    gears, bearings = scenario.gears, scenario.bearings
    return LoadOnShaftSpec.model_construct(
        mass=spec.mass, shaft="drum", rope_radius=0.5 * scenario.drum.diameter, rope=scenario.rope,
        ground=scenario.ground, buffer=scenario.buffer,
        bearings=None if bearings is None else LoadBearingsSpec.model_construct(
            gear_offset=bearings.gear_offset, rope_offset=bearings.rope_offset, span=bearings.span,
            wheel_pitch_diameter=gears.module * gears.wheel_teeth, pressure_angle=gears.pressure_angle),
    ).with_resolved(gravity=scenario.gravity, start_speed=scenario.initial.drum_speed)


def clutch_as_drawn(spec, scenario) -> FrictionClutchSpec:
    """The hoist's ``clutch:`` (and ``clutch_heating:``) as the drivetrain's clutch ``clutch``: a friction clutch
    from the motor shaft to the pinion shaft, pressed by the engagement force, with its heating."""
    table = spec.engagement_force
    cone = ConeSpec.model_construct(inner_radius=spec.inner_radius, outer_radius=spec.outer_radius,
                                    half_angle=spec.half_angle, mean_radius=spec.mean_radius)
    force = TimeSignal.model_construct(times=table.times, values=table.forces, amplitudes=(), frequencies=(),
                                       phases=())
    return FrictionClutchSpec.model_construct(
        name="clutch", between=("motor", "pinion"), static_friction=spec.static_friction,
        kinetic_friction=spec.kinetic_friction, surfaces=spec.surfaces, effective_radius=None, cone=cone, force=force,
        heating=scenario.clutch_heating,
    ).with_resolved(halves=(spec.driving_inertia, spec.driven_inertia), on_line=False)  # its halves' inertias


def heating_as_drawn(spec, scenario) -> FrictionClutchSpec:
    """``clutch_heating:``: the drawn clutch's heating (its element reads the heating and the clutch's name)."""
    return FrictionClutchSpec.model_construct(name="clutch", heating=spec)


def slider_crank_as_drawn(spec, scenario) -> SliderCrankSpec:
    """``reciprocating:``: a slider-crank named reciprocating on the motor shaft (outputs slider_position,
    reciprocating_inertia)."""
    return SliderCrankSpec.model_construct(name="reciprocating", shaft="motor", mass=spec.mass,
                                           crank_radius=spec.crank_radius, rod_length=spec.rod_length)


def brake_as_drawn(spec, scenario) -> BrakeOnShaftSpec:
    """``brake:``: a brake named brake on the drum shaft."""
    return BrakeOnShaftSpec.model_construct(**{name: getattr(spec, name) for name in type(spec).model_fields},
                                            name="brake", shaft="drum")


def ratchet_as_drawn(spec, scenario) -> RatchetOnShaftSpec:
    """``ratchet:``: a pawl named ratchet on the drum shaft."""
    return RatchetOnShaftSpec.model_construct(release_time=spec.release_time, name="ratchet", shaft="drum")


def the_load(spec, scenario) -> LoadOnShaftSpec:
    """A section of the load's (its rope, the ground, its buffer, the drum shaft's bearings): the drawn load, which holds it."""
    return load_as_drawn(scenario.load, scenario)


def periodic_as_drawn(spec: PeriodicSpec, scenario) -> PeriodicSpec:
    """A section that is no part of the machine but an analysis of its run (the periodic regime), with the
    machine's period written in (rad of motor angle: when every periodic part is back where it started,
    :func:`.period.machine_period`) and whether an inertia varies with the angle (a slider-crank: the energy
    guards stay on)."""
    return spec.with_resolved(period=machine_period(scenario),
                              inertia_varies_with_angle=scenario.reciprocating is not None)


# Each hoist section (dotted within another) -> the drawn parts it stands for, in the order of the machine's
# bodies, states and columns.
TEMPLATE: dict[str, tuple[TemplatePart, ...]] = {
    "motor": (TemplatePart("drivetrain.shafts.*", motor_shaft_as_drawn, name="motor"),
              TemplatePart("drivetrain.motors.*", motor_as_drawn, name="motor")),
    "motor.ripple": (TemplatePart("drivetrain.motors.*.ripple", motor_ripple_as_drawn, MOTOR_RIPPLE_NAMES),),
    "gears": (TemplatePart("drivetrain.shafts.*", pinion_shaft_as_drawn, PINION_NAMES, "pinion"),
              TemplatePart("drivetrain.shafts.*", drum_shaft_as_drawn, name="drum")),
    "gears.mesh": (TemplatePart("drivetrain.gears.*.mesh", mesh_as_drawn, MESH_NAMES),),
    "clutch": (TemplatePart("drivetrain.clutches.*", clutch_as_drawn, CLUTCH_NAMES, "clutch"),),
    "clutch_heating": (TemplatePart("drivetrain.clutches.*.heating", heating_as_drawn, HEATING_NAMES),),
    "drum": (TemplatePart("drivetrain.rotors.*", drum_as_drawn, name="drum"),),
    "drum.resisting_ripple": (TemplatePart("drivetrain.shafts.*.resisting_ripple", drum_ripple_as_drawn,
                                           DRUM_RIPPLE_NAMES),),
    "load": (TemplatePart("drivetrain.load", load_as_drawn),),
    "rope": (TemplatePart("drivetrain.load.rope", the_load),),
    "ground": (TemplatePart("drivetrain.load.ground", the_load),),
    "buffer": (TemplatePart("drivetrain.load.buffer", the_load),),
    "flywheel": (TemplatePart("drivetrain.rotors.*", flywheel_as_drawn, name="flywheel"),),
    "reciprocating": (TemplatePart("drivetrain.slider_cranks.*", slider_crank_as_drawn, SLIDER_CRANK_NAMES,
                                   "reciprocating"),),
    "brake": (TemplatePart("drivetrain.brakes.*", brake_as_drawn, name="brake"),),
    "ratchet": (TemplatePart("drivetrain.ratchets.*", ratchet_as_drawn, name="ratchet"),),
    "bearings": (TemplatePart("drivetrain.load.bearings", the_load),),
    "periodic_regime": (TemplatePart("periodic_regime", periodic_as_drawn),),
}

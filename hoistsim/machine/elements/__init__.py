"""The parts of the machine, one file each, and the registry that builds a scene's elements.

A scenario section that is present builds its element (or elements); a section that is
absent builds nothing, so the scene has none of its bodies, states, terms,
guards or columns.  Variants of a section (the load on a rigid or an elastic rope) are
alternatives picked by the keys given, each in its own file.  Every scenario is lowered first to the drawn
drivetrain's parts (:mod:`hoistsim.scenario.lowering`; a hoist's are the ones its template writes out): an element
is built from its part's spec alone, and one element class serves a part in either form.
"""

from __future__ import annotations

from ...scenario.lowering import lower
from ..core.element import AbstractCoupling as AbstractCoupling
from ..core.element import AbstractElement as AbstractElement
from .acceleration_source import AccelerationSource as AccelerationSource
from .angle_source import AngleSource as AngleSource
from .bearing_friction import BearingFriction as BearingFriction
from .bearings import DrumShaftLoads as DrumShaftLoads
from .clutch_heating import ClutchHeating as ClutchHeating
from .constant_torque_motor import ConstantTorqueMotor as ConstantTorqueMotor
from .dc_machine import DcMachine as DcMachine
from .eddy_current_brake import EddyCurrentBrake as EddyCurrentBrake
from .elastic_load import ElasticLoad as ElasticLoad
from .elasto_backlash import ElastoBacklash as ElastoBacklash
from .elasto_gap import ElastoGap as ElastoGap
from .flywheel import Flywheel as Flywheel
from .friction_brake import FrictionBrake as FrictionBrake
from .friction_clutch import FrictionClutch as FrictionClutch
from .ground import Ground as Ground
from .heat_capacitor import HeatCapacitor as HeatCapacitor
from .holding_brake import HoldingBrake as HoldingBrake
from .housed_gear import HousedGear as HousedGear
from .induction_machine import InductionMachine as InductionMachine
from .level_load import LevelLoad as LevelLoad
from .line_force import LineForce as LineForce
from .linear_motor import LinearMotor as LinearMotor
from .linear_torque import LinearTorque as LinearTorque
from .load_buffer import LoadBuffer as LoadBuffer
from .load_drag import LoadDrag as LoadDrag
from .lossy_gear import LossyGear as LossyGear
from .lower_stop import LowerStop as LowerStop
from .mass import Mass as Mass
from .mesh_friction import MeshFriction as MeshFriction
from .motor import Motor as Motor
from .motor_ripple import MotorRipple as MotorRipple
from .motor_table import TableMotor as TableMotor
from .one_way_clutch import OneWayClutch as OneWayClutch
from .operated_brake import OperatedBrake as OperatedBrake
from .periodic_regime import PeriodicRegime as PeriodicRegime
from .planetary import Planetary as Planetary
from .quadratic_torque import QuadraticTorque as QuadraticTorque
from .ratchet import Ratchet as Ratchet
from .resisting_ripple import ResistingRipple as ResistingRipple
from .rigid_load import RigidLoad as RigidLoad
from .rope import Rope as Rope
from .shaft import Shaft as Shaft
from .shaft_torque import ShaftTorque as ShaftTorque
from .slider_crank import SliderCrank as SliderCrank
from .speed_controller import SpeedController as SpeedController
from .speed_source import SpeedSource as SpeedSource
from .speed_table_torque import SpeedTableTorque as SpeedTableTorque
from .spring_damper import SpringDamper as SpringDamper
from .upper_stop import UpperStop as UpperStop
from .vehicle import Vehicle as Vehicle
from .wire_rope import WireRope as WireRope

# A drawn drivetrain's part (each part of a kind: "*"; a key within a part: dotted after it) -> its element, or the
# variant's name -> element for a part with variants (its spec's ``characteristic``).  A key within a part (a
# motor's ripple) is built from the part that holds it.  The order is the order of bodies, states and output
# columns of every machine, a hoist's as a drawn drivetrain's (one program for a hoist and the drivetrain it stands
# for).
REGISTRY: dict[str, object] = {
    "drivetrain.shafts.*": Shaft,
    "drivetrain.shafts.*.resisting_ripple": ResistingRipple,
    "drivetrain.masses.*": Mass,
    "drivetrain.rotors.*": Flywheel,
    "drivetrain.slider_cranks.*": SliderCrank,
    "drivetrain.motors.*": Motor,
    "drivetrain.motors.*.ripple": MotorRipple,
    "drivetrain.dc_machines.*": DcMachine,
    "drivetrain.induction_machines.*": InductionMachine,
    "drivetrain.speed_controllers.*": SpeedController,
    # drives, before the couplings that yield: a shaft held by a drive and a hold is held by the drive
    "drivetrain.motion_sources.*": {"speed": SpeedSource, "angle": AngleSource, "acceleration": AccelerationSource},
    "drivetrain.torques.*": {"time": ShaftTorque, "speed_table": SpeedTableTorque, "quadratic": QuadraticTorque,
                             "linear": LinearTorque},
    "drivetrain.forces.*": LineForce,
    "drivetrain.vehicles.*": Vehicle,
    # linkages of three shafts, before the friction couplings: where stuck couplings hold one motion twice,
    # the first in order takes the torque, and these hold any
    "drivetrain.gears.*.housing": HousedGear,  # a stage whose housing turns
    "drivetrain.planetaries.*": Planetary,
    # a mass's stops, before its friction: resting against one, the stop takes a push before the friction would
    "drivetrain.stops.*.lower": LowerStop,
    "drivetrain.stops.*.upper": UpperStop,
    "drivetrain.clutches.*": FrictionClutch,
    "drivetrain.clutches.*.heating": ClutchHeating,
    "drivetrain.one_way_clutches.*": OneWayClutch,
    "drivetrain.bearing_frictions.*": BearingFriction,
    "drivetrain.springs.*": {"spring": SpringDamper, "backlash": ElastoBacklash, "gap": ElastoGap},
    # a lossy stage's mesh: constant efficiencies (the hoist's), or Modelica's lossTable
    "drivetrain.gears.*.mesh": {"efficiency": MeshFriction, "loss_table": LossyGear},
    "drivetrain.load": {"rigid": RigidLoad, "elastic": ElasticLoad,  # on a rigid rope, or a body on its rope,
                        "level": LevelLoad},  # or moved along a level path
    "drivetrain.load.drag": LoadDrag,
    "drivetrain.load.rope": {"stiffness": Rope, "modulus": WireRope},
    "drivetrain.load.ground": Ground,
    "drivetrain.load.buffer": LoadBuffer,
    "drivetrain.brakes.*": {"holding": HoldingBrake, "friction": FrictionBrake, "operated": OperatedBrake},
    "drivetrain.ratchets.*": Ratchet,
    "drivetrain.load.bearings": DrumShaftLoads,
    "drivetrain.eddy_current_brakes.*": EddyCurrentBrake,
    "drivetrain.heat_capacitors.*": HeatCapacitor,  # after the brakes: a brake's heat warms one
    "periodic_regime": PeriodicRegime,  # an analysis of the hoist's run: given, or implied by a ripple
}


def element_sections(scenario) -> list[tuple[str, object, object]]:
    """(section, its part's drawn spec, the element class that builds it) for each element the scenario builds,
    in the registry's order (the parts :func:`hoistsim.scenario.lowering.lower` writes out)."""
    return [(part.section, part.spec, element_class(part)) for part in lower(scenario, REGISTRY).parts]


def element_class(part) -> type:
    """The element class that builds a lowered part: its registry path's, its variant's (its spec's
    ``characteristic``) for a path with variants."""
    entry = REGISTRY[part.path]
    return entry[part.held.characteristic] if isinstance(entry, dict) else entry


def elements_for(scenario) -> tuple[AbstractElement, ...]:
    """The elements a scenario names, each built from its part's spec alone, in order (a hoist's on the scenario
    started at its steady lift, where it asks)."""
    return tuple(cls.from_spec(spec) for _, spec, cls in element_sections(scenario))

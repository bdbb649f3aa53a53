"""The parts of the machine, one file each, and the registry that builds a scene's elements.

A scenario section that is present builds its element (or elements); a section that is
absent builds nothing, so the scene has none of its bodies, states, terms,
guards or columns.  Variants of a section (the load on a rigid or an elastic rope) are
alternatives picked by the keys given, each in its own file.  A hoist section that the hoist's
template writes out as a drawn drivetrain's part (:class:`Drawn`) builds that part's element.
"""

from __future__ import annotations

from ..core.element import AbstractCoupling as AbstractCoupling
from ..core.element import AbstractElement as AbstractElement
from ...scenario.hoist_template import (clutch_as_drawn, drum_as_drawn, drum_shaft_as_drawn, load_as_drawn,
                                        mesh_as_drawn, motor_as_drawn, motor_shaft_as_drawn, pinion_shaft_as_drawn)
from ._drawn import Drawn as Drawn
from .bearings import DrumShaftLoads as DrumShaftLoads
from .clutch_heating import ClutchHeating as ClutchHeating
from .constant_torque_motor import ConstantTorqueMotor as ConstantTorqueMotor
from .elastic_load import ElasticLoad as ElasticLoad
from .flywheel import Flywheel as Flywheel
from .friction_brake import FrictionBrake as FrictionBrake
from .friction_clutch import FrictionClutch as FrictionClutch
from .ground import Ground as Ground
from .holding_brake import HoldingBrake as HoldingBrake
from .linear_motor import LinearMotor as LinearMotor
from .mesh_friction import MeshFriction as MeshFriction
from .motor import Motor as Motor
from .motor_ripple import MotorRipple as MotorRipple
from .motor_table import TableMotor as TableMotor
from .periodic_regime import PeriodicRegime as PeriodicRegime
from .ratchet import Ratchet as Ratchet
from .resisting_ripple import ResistingRipple as ResistingRipple
from .rigid_load import RigidLoad as RigidLoad
from .rope import Rope as Rope
from .shaft import Shaft as Shaft
from .shaft_torque import ShaftTorque as ShaftTorque
from .slider_crank import SliderCrank as SliderCrank
from .wire_rope import WireRope as WireRope

# Scenario section (dotted within another) -> its element, the variant's name -> element for a section
# with variants, or a tuple of them for a section that builds several.
# The order is the order of bodies, states and output columns.
REGISTRY: dict[str, object] = {
    # the motor shaft and the motor on it, drawn by the template
    "motor": (Drawn(Shaft, motor_shaft_as_drawn, ("initial",)), Drawn(Motor, motor_as_drawn)),
    "motor.ripple": MotorRipple,
    # the pinion shaft (a body) and the drum shaft geared to it, drawn by the template
    "gears": (Drawn(Shaft, pinion_shaft_as_drawn, ("initial",)), Drawn(Shaft, drum_shaft_as_drawn, ("initial",))),
    # a lossy mesh's friction: scenario.gears.mesh, given with an efficiency
    "gears.mesh": Drawn(MeshFriction, mesh_as_drawn),
    "clutch": Drawn(FrictionClutch, clutch_as_drawn, ("clutch_heating",)),  # the cone clutch: a friction clutch, drawn by the template
    "clutch_heating": ClutchHeating,
    "drum": Drawn(Flywheel, drum_as_drawn),  # the drum's own inertia, a rotor on the drum shaft
    "drum.resisting_ripple": ResistingRipple,
    "load": {"rigid": Drawn(RigidLoad, load_as_drawn, ("drum", "gravity")), "elastic": ElasticLoad},  # on a rigid rope, or a body of its own on rope:
    "rope": {"stiffness": Rope, "modulus": WireRope},
    "ground": Ground,
    "flywheel": Flywheel,
    "reciprocating": SliderCrank,
    "brake": {"holding": HoldingBrake, "friction": FrictionBrake},
    "ratchet": Ratchet,
    "bearings": DrumShaftLoads,
    "periodic_regime": PeriodicRegime,  # scenario.periodic_regime: given, or implied by a ripple
    # a machine drawn as shafts and couplings (instead of the hoist's sections): each part of a kind ("*")
    "drivetrain.shafts.*": Shaft,
    "drivetrain.motors.*": Motor,
    "drivetrain.torques.*": ShaftTorque,
    "drivetrain.clutches.*": FrictionClutch,
    "drivetrain.gears.*.mesh": MeshFriction,  # a lossy stage's mesh
    "drivetrain.load": RigidLoad,
}


def _variant(section: str, spec, scenario) -> str:
    """The variant of a section with variants: its spec's ``characteristic``, or for the load, whether
    the scene gives it a rope of its own."""
    if section == "load":
        return "rigid" if scenario.rope is None else "elastic"
    return spec.characteristic


def element_sections(scenario) -> list[tuple[str, object, type]]:
    """(section, its spec, what builds the element) for each element the scenario's sections build, in
    registry order (a section that builds several: a row each; a drawn part: its own section, named)."""
    out = []
    for path, parts, entry in _PATHS:
        for section, spec in _parts_of(scenario, parts) if "*" in parts else ((path, _section(scenario, parts)),):
            if spec is None:
                continue
            for one in entry if isinstance(entry, tuple) else (entry,):
                out.append((section, spec, one[_variant(section, spec, scenario)] if isinstance(one, dict) else one))
    return out


# each registry path split once: (path, its parts, its entry)
_PATHS = [(path, tuple(path.split(".")), entry) for path, entry in REGISTRY.items()]


def _section(holder, parts: tuple):
    """What a dotted path names within ``holder`` (a section within a section: motor.ripple), None where absent."""
    for part in parts:
        holder = getattr(holder, part, None)
        if holder is None:
            return None
    return holder


def _parts_of(scenario, parts: tuple) -> list:
    """(dotted section, its spec) of each part a path with ``*`` names: drivetrain.clutches.* gives
    drivetrain.clutches.<name> for each clutch, drivetrain.torques.* drivetrain.torques.<index>."""
    found = [("", scenario)]
    for part in parts:
        if part == "*":
            found = [(f"{where}.{key}", member) for where, holder in found
                     for key, member in (holder.items() if isinstance(holder, dict) else enumerate(holder))]
        else:
            found = [(f"{where}.{part}" if where else part, getattr(holder, part, None)) for where, holder in found]
            found = [(where, holder) for where, holder in found if holder is not None]
    return found


def elements_for(scenario) -> tuple[AbstractElement, ...]:
    """The elements a scenario names, built from their sections, in registry order."""
    return tuple(cls.from_spec(spec, scenario) for _, spec, cls in element_sections(scenario))

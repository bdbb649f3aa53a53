"""A drivetrain drawn as shafts and couplings: the elements of ``drivetrain:``, each the element of its kind."""

from __future__ import annotations

from ._signal import signal_fields
from .friction_clutch import FrictionClutch
from .mesh_friction import MeshFriction
from .motor import Motor
from .rigid_load import RigidLoad
from .shaft import Shaft
from .shaft_torque import ShaftTorque


class Drivetrain:
    """Builds a drivetrain's elements: its shafts (a body per gear train: its first shaft, the others
    geared to it), the motors and torques on them, its clutches, the losses of its lossy gear stages, the
    load hanging from one."""

    @staticmethod
    def from_spec(spec, scenario) -> tuple:
        shafts = [Shaft.from_spec(s, scenario) for s in spec.shafts.values()]
        shafts.sort(key=lambda shaft: bool(shaft.geared_to))  # the bodies first, then what is geared to them
        motors = [Motor.from_spec(m, scenario) for m in spec.motors.values()]
        torques = [ShaftTorque(**signal_fields(t.torque, "torque"), shaft=t.shaft, section=f"torque{i + 1}")
                   for i, t in enumerate(spec.torques)]
        clutches = [FrictionClutch.from_spec(c, scenario) for c in spec.clutches.values()]
        meshes = [MeshFriction.from_spec(stage, scenario) for stage in spec.gears.values() if stage.lossy]
        load = [] if spec.load is None else [RigidLoad.from_spec(spec.load, scenario)]
        return (*shafts, *motors, *torques, *clutches, *meshes, *load)

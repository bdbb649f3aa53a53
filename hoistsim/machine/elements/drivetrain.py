"""A drivetrain drawn as shafts and couplings: the elements of ``drivetrain:``, each the element of its kind."""

from __future__ import annotations

from ...scenario.schema_drivetrain import beyond_stage, gear_groups
from ._motor_variants import MOTOR_VARIANTS
from ._signal import signal_fields
from .friction_clutch import FrictionClutch
from .mesh_friction import MeshFriction
from .rigid_load import RigidLoad
from .shaft import Shaft
from .shaft_motor import ShaftMotor
from .shaft_torque import ShaftTorque


class Drivetrain:
    """Builds a drivetrain's elements: its shafts (a body per gear train: its first shaft, the others
    geared to it), the motors and torques on them, its clutches, the losses of its lossy gear stages, the
    load hanging from one."""

    @staticmethod
    def from_spec(spec, scenario) -> tuple:
        groups = gear_groups(spec)
        shafts = [Shaft(inertia=s.inertia, initial_speed=spec.shafts[groups[name][0]].speed * groups[name][1],
                        speed_ratio=groups[name][1], section=name,
                        geared_to="" if groups[name][0] == name else groups[name][0])
                  for name, s in spec.shafts.items()]
        shafts.sort(key=lambda shaft: bool(shaft.geared_to))  # the bodies first, then what is geared to them
        motors = [ShaftMotor.from_spec(name, m, MOTOR_VARIANTS) for name, m in spec.motors.items()]
        torques = [ShaftTorque(**signal_fields(t.torque, "torque"), shaft=t.shaft, section=f"torque{i + 1}")
                   for i, t in enumerate(spec.torques)]
        clutches = [FrictionClutch.from_spec(c, scenario) for c in spec.clutches.values()]
        meshes = [MeshFriction.in_stage(name, stage, beyond_stage(spec, name))
                  for name, stage in spec.gears.items() if stage.lossy]
        load = [] if spec.load is None else [RigidLoad.on_shaft(spec.load, scenario)]
        return (*shafts, *motors, *torques, *clutches, *meshes, *load)

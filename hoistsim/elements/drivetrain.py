"""A drivetrain drawn as shafts and couplings: the elements of ``drivetrain:``, each the element of its kind."""

from __future__ import annotations

from .friction_clutch import FrictionClutch
from .shaft import Shaft
from .shaft_torque import ShaftTorque
from ._signal import signal_fields


class Drivetrain:
    """Builds a drivetrain's elements: its shafts (bodies), the torques on them, its clutches."""

    parts = (Shaft, ShaftTorque, FrictionClutch)  # the kinds of element it builds (what a file may hold)

    @staticmethod
    def from_spec(spec, scenario) -> tuple:
        shafts = [Shaft(inertia=s.inertia, initial_speed=s.speed, section=name) for name, s in spec.shafts.items()]
        torques = [ShaftTorque(**signal_fields(t.torque, "torque"), shaft=t.shaft, section=f"torque{i + 1}")
                   for i, t in enumerate(spec.torques)]
        clutches = [FrictionClutch.from_spec(name, c) for name, c in spec.clutches.items()]
        return (*shafts, *torques, *clutches)

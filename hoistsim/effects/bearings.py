"""Drum-shaft loads in time: tooth forces at the mesh, rope tension, bearing reactions."""

from __future__ import annotations

import math
from typing import ClassVar

import jax.numpy as jnp

from ..components import DrumShaft
from ._base import AbstractEffect, RowContext

_NAMES = ("tooth_tangential_force", "tooth_radial_force", "tooth_force", "rope_tension",
          "bearing_A_x", "bearing_A_y", "bearing_A", "bearing_B_x", "bearing_B_y", "bearing_B")


class DrumShaftLoads(AbstractEffect):
    """The exercise's question 3 at every output row, with the inertia forces of the start.

    The tooth force comes from the torque the pinion actually passes to the wheel:
    the clutch torque less what accelerates the driven clutch half and the pinion.
    The rope tension is M (g + a) with a the load's acceleration.  Adds no state
    and no term to the equations of motion: only output columns.
    """

    pinion_pitch_radius: object  # r1, m
    tan_pressure_angle: object
    pinion_side_inertia: object  # kg*m^2: driven clutch half + pinion
    load_mass: object  # kg
    gravity: object  # m/s^2
    gear_offset: object  # m
    rope_offset: object  # m
    span: object  # m

    section: ClassVar[str] = "bearings"
    output_units: ClassVar[dict[str, str]] = {name: "N" for name in _NAMES}

    @classmethod
    def from_spec(cls, spec, scenario) -> "DrumShaftLoads":
        gears = scenario.gears
        return cls(
            pinion_pitch_radius=0.5 * gears.module * gears.pinion_teeth,
            tan_pressure_angle=math.tan(gears.pressure_angle),
            pinion_side_inertia=scenario.clutch.driven_inertia + gears.pinion_inertia,
            load_mass=scenario.load.mass,
            gravity=scenario.gravity,
            gear_offset=spec.gear_offset,
            rope_offset=spec.rope_offset,
            span=spec.span,
        )

    def outputs(self, row: RowContext, drivetrain) -> dict:
        teeth_torque = row.clutch_torque - self.pinion_side_inertia * row.output_acceleration
        tangential = teeth_torque / self.pinion_pitch_radius
        radial = jnp.abs(tangential) * self.tan_pressure_angle
        load_acceleration = drivetrain.rope_radius * row.output_acceleration / drivetrain.ratio
        rope_tension = self.load_mass * (self.gravity + load_acceleration)
        shaft = DrumShaft(self.gear_offset, self.rope_offset, self.span)
        return {
            "tooth_tangential_force": tangential,
            "tooth_radial_force": radial,
            "tooth_force": jnp.hypot(tangential, radial),
            "rope_tension": rope_tension,
            **shaft.reactions(tangential, radial, rope_tension),
        }

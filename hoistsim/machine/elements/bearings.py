"""Drum-shaft loads in time: tooth forces at the mesh, rope tension, bearing reactions."""

from __future__ import annotations

import math
from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from ...components import DrumShaft
from ..core.element import AbstractElement

_DESCRIPTIONS = {
    "tooth_tangential_force": "tooth force along the pitch-circle tangent, from the torque the wheel receives",
    "tooth_radial_force": "separating tooth force, T tan(pressure angle)",
    "tooth_force": "total tooth force",
    "rope_tension": "rope tension: M (g + a) on a rigid rope, the rope's force on an elastic one",
    "bearing_A_x": "bearing A reaction in the plane of the tangential tooth force",
    "bearing_A_y": "bearing A reaction in the plane of the radial tooth force and the rope",
    "bearing_A": "bearing A reaction, magnitude",
    "bearing_B_x": "bearing B reaction in the plane of the tangential tooth force",
    "bearing_B_y": "bearing B reaction in the plane of the radial tooth force and the rope",
    "bearing_B": "bearing B reaction, magnitude",
}


class DrumShaftLoads(AbstractElement):
    """The exercise's question 3 at every output row, with the inertia forces of the start.

    The tooth force comes from the torque the wheel actually receives, the tooth
    load: what the drum shaft's inertia, load, brake and pawl take from it (with
    a lossy mesh, less than the pinion gives by the flanks' friction).
    The rope tension is M (g + a) with a the load's acceleration on a rigid
    rope; on an elastic rope (``rope:``) it is the rope's own force, what pulls
    the drum's rope point down.  Adds no state and no term to the equations of
    motion: only output columns.
    """

    wheel_pitch_radius: object  # r2, m
    tan_pressure_angle: object
    load_mass: object  # kg
    gravity: object  # m/s^2
    rope_radius: object  # m
    gear_offset: object  # m
    rope_offset: object  # m
    span: object  # m
    elastic_rope: bool = static(False)
    drum: str = static("drum")  # the shaft the load hangs from, which the wheel drives

    section: ClassVar[str] = "bearings"
    columns: ClassVar[dict] = {name: ("N", text) for name, text in _DESCRIPTIONS.items()}

    @classmethod
    def from_spec(cls, spec) -> "DrumShaftLoads":
        bearings = spec.bearings
        return cls(
            wheel_pitch_radius=0.5 * bearings.wheel_pitch_diameter,
            tan_pressure_angle=math.tan(bearings.pressure_angle),
            load_mass=spec.mass,
            gravity=spec.resolved("gravity"),
            rope_radius=spec.rope_radius,
            gear_offset=bearings.gear_offset,
            rope_offset=bearings.rope_offset,
            span=bearings.span,
            elastic_rope=spec.rope is not None,
            drum=spec.shaft,
        )

    def outputs(self, x) -> dict:
        tangential = x.torque_into(self.drum) / self.wheel_pitch_radius
        radial = jnp.abs(tangential) * self.tan_pressure_angle
        if self.elastic_rope:  # what the rope pulls the drum's rope point down with
            rope_tension = -x.shaft_torques["rope_point"]
        else:
            rope_tension = self.load_mass * (self.gravity + self.rope_radius * x.acceleration(self.drum))
        shaft = DrumShaft(self.gear_offset, self.rope_offset, self.span)
        return {
            "tooth_tangential_force": tangential,
            "tooth_radial_force": radial,
            "tooth_force": jnp.hypot(tangential, radial),
            "rope_tension": rope_tension,
            **shaft.reactions(tangential, radial, rope_tension),
        }

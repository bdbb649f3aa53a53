"""The keys of a friction clutch, values in SI: its friction and a cone's faces, written once for the hoist's
clutch (``clutch:``) and a drawn drivetrain's (``drivetrain.clutches``)."""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, model_validator

from ..components import ConeClutch
from ..errors import ScenarioError
from . import plausible
from . import units as u
from .schema_base import Section


class FrictionSpec(Section):
    """Faces that stick below static_friction * force * lever and slide at kinetic_friction * force * lever."""

    static_friction: u.quantity(u.DIMENSIONLESS, gt=0.0) = Field(description="mu_s: the faces stick below it")
    kinetic_friction: u.quantity(u.DIMENSIONLESS, ge=0.0) = Field(description="mu_k, sliding (not above "
                                                                  "static_friction)")
    surfaces: u.whole("friction surfaces") = Field(1, description="n, the faces in contact")

    @model_validator(mode="after")
    def _sliding_within_sticking(self):
        if self.kinetic_friction > self.static_friction:
            raise ScenarioError(".kinetic_friction", f"must not exceed static_friction ({self.static_friction:g}), "
                                f"got {self.kinetic_friction:g}")
        return self


class ConeSpec(Section):
    """A cone's faces: their wedge multiplies the axial force pressing them (the effective radius n r_m / sin beta)."""

    inner_radius: u.quantity(u.LENGTH, plausible=plausible.CLUTCH_FACE_RADIUS, gt=0.0) = Field(
        description="r_i of the faces (less than outer_radius)")
    outer_radius: u.quantity(u.LENGTH, plausible=plausible.CLUTCH_FACE_RADIUS, gt=0.0) = Field(
        description="r_e of the faces")
    half_angle: u.quantity(u.ANGLE, " (the cone half-angle beta = 90 deg - delta)", gt=0.0, lt=math.pi / 2) = Field(
        description="beta, the cone's half-angle (exercise 6's delta = 65 deg is 90 deg - beta)")
    mean_radius: Literal["uniform_wear", "uniform_pressure"] = Field("uniform_wear", description="r_m: "
                                                                     "uniform_wear (r_i + r_e) / 2, or "
                                                                     "uniform_pressure's")

    @model_validator(mode="after")
    def _an_annulus(self):
        if self.inner_radius >= self.outer_radius:
            raise ScenarioError(".inner_radius", f"must be less than outer_radius ({self.outer_radius:g} m), "
                                f"got {self.inner_radius:g} m")
        return self

    def torque_per_newton(self, surfaces: int) -> float:
        """m: the friction torque each newton of axial force gives, per unit friction coefficient, with
        ``surfaces`` faces: c = n r_m / sin(beta) (:class:`hoistsim.components.ConeClutch`)."""
        return ConeClutch(self.inner_radius, self.outer_radius, self.half_angle, 1.0, 1.0, surfaces,
                          self.mean_radius).torque_per_newton

"""A drawn drivetrain's friction clutches (``drivetrain.clutches``) and one-way clutches
(``drivetrain.one_way_clutches``): faces pressed by a force that is a time signal (values in SI)."""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import tables
from . import units as u
from .schema_clutch import ConeSpec, FrictionSpec
from .schema_masses import LineKeys, line_starts
from .schema_parts import ClutchHeatingSpec, fade_tables, kinetic_within_static
from .schema_shaft_parts import OnShaft
from .signals import signal
from .units import Text


class FrictionClutchSpec(OnShaft, FrictionSpec):
    """A friction clutch between two shafts, or a shaft and the ground (a brake): faces (static_friction,
    kinetic_friction, surfaces: as the hoist's clutch's) on a lever, an effective radius or a cone's, pressed
    by a force that is a time signal; their heat, where ``heating`` is
    given, a lump with its temperature (the friction against it, where it gives tables).  The kinetic friction
    may be a table of the slip speed (Modelica's mu_pos), the static friction then given as its ``peak``
    factor over the kinetic friction at zero slip (Modelica's peak) or as a coefficient."""

    alternatives = (("static_friction", "peak"), ("effective_radius", "cone"))
    line_keys: ClassVar[LineKeys] = LineKeys("between", line_only=("geometry_constant",),
                                             shafts_only=("effective_radius", "cone", "heating"))
    static_friction: u.quantity(u.DIMENSIONLESS, gt=0.0) | None = Field(None, description="mu_s: the faces stick "
                                                                        "below it")
    # a constant, or rows [slip speed, coefficient]: the friction at a slip either way, flat beyond the rows
    kinetic_friction: tables.SlipFriction = Field(description="mu_k: a constant, or a table of the slip speed's "
                                                  "size (Modelica's mu_pos), flat beyond the rows")
    peak: u.quantity(u.DIMENSIONLESS, ge=1.0) | None = Field(None, description="static_friction = peak times the "
                                                             "kinetic friction at zero slip (Modelica's peak)")
    between: tuple[Text, Text] = Field(description="[shaft a, shaft b or ground]: its torque passes from a to b")
    effective_radius: u.quantity(u.LENGTH, gt=0.0) | None = Field(None, description="the faces' lever: torque = "
                                                                  "mu force effective_radius surfaces")
    cone: ConeSpec | None = Field(None, description="a cone's faces, whose geometry gives the lever")
    geometry_constant: u.quantity(u.DIMENSIONLESS, gt=0.0) | None = Field(None, description="between masses (a "
                                                                          "brake on a line, Modelica's cgeo): "
                                                                          "force = mu force geometry_constant "
                                                                          "surfaces (default 1)")
    force: signal(u.FORCE) = Field(description="pressing the faces; at or below zero the clutch is open")
    heating: ClutchHeatingSpec | None = Field(None, description="its faces' heat: a lump with its temperature")
    name: str = Field("", exclude=True)  # its key in drivetrain.clutches (set there, never written)

    def _sliding_within_sticking(self):  # in place of FrictionSpec's: static_friction or peak, over a table
        if (self.static_friction is None) == (self.peak is None):
            raise ScenarioError(".static_friction", "give either static_friction or peak (static_friction = peak * "
                                "the kinetic friction at zero slip), one of them")
        if self.peak is not None:
            self._derive("static_friction", self.peak * self.kinetic_at_rest)
        elif self.kinetic_at_rest > self.static_friction:
            raise ScenarioError(".kinetic_friction", f"must not exceed static_friction ({self.static_friction:g}) at "
                                f"zero slip, got {self.kinetic_at_rest:g}")
        if self.slip_table is not None and self.heating is not None and self.heating.fades:
            raise ScenarioError(".kinetic_friction", "is a table of the slip speed, and heating gives friction against "
                                "the temperature: give one of them")
        return self

    @model_validator(mode="after")
    def _kinetic_within_static_when_hot(self):
        if self.heating is not None and self.slip_table is None:
            kinetic_within_static(self.heating, self.static_friction, self.kinetic_friction, ".heating")
        return self

    @property
    def slip_table(self) -> tuple | None:
        """The kinetic friction's rows [slip speed (rad/s), coefficient], or None where it is a constant."""
        return self.kinetic_friction if isinstance(self.kinetic_friction, tuple) else None

    @property
    def kinetic_at_rest(self) -> float:
        """The kinetic friction at zero slip: the constant, or the table's first row."""
        table = self.slip_table
        return self.kinetic_friction if table is None else table[0][1]

    @property
    def torque_per_newton(self) -> float:
        """m: the torque each newton of force gives, per unit friction coefficient (a cone's wedge in it)."""
        if self.effective_radius is None and self.cone is None:  # on a line: a force per newton, no lever
            return (self.geometry_constant or 1.0) * self.surfaces
        if self.cone is None:
            return self.effective_radius * self.surfaces
        return self.cone.torque_per_newton(self.surfaces)

    def lowered(self, scenario) -> "FrictionClutchSpec":
        """With the inertias of its halves on shaft a and on shaft b written in (kg*m^2; a drawn clutch's halves
        are its shafts': none)."""
        return self.with_resolved(halves=(0.0, 0.0),
                                  on_line=not line_starts(scenario.drivetrain).keys().isdisjoint(self.between))

    def fade(self) -> dict | None:
        """Its friction against its faces' temperature (tables on common knots), None for constant friction."""
        heating = self.heating
        return fade_tables(heating, self) if heating is not None and heating.fades else None


class OneWayClutchSpec(FrictionClutchSpec):
    """A freewheel and a friction clutch side by side (Modelica's OneWayClutch): shaft b (the second of
    ``between``) may overrun shaft a, never a overrun b; the clutch's keys, but no ground (a freewheel to the
    ground is a ratchet) and no heating."""

    @model_validator(mode="after")
    def _no_heating(self):
        if self.heating is not None:
            raise ScenarioError(".heating", "is not a key of a one-way clutch (its heat is <name>_energy)")
        return self

"""A drawn drivetrain's vehicles (``drivetrain.vehicles``): the driving resistances on a mass that is a vehicle's
body (values in SI)."""

from __future__ import annotations

from pydantic import Field

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .signals import signal
from .units import Text


class DragSpec(Section):
    """The air's drag on a vehicle: Cd A rho (v - v_wind)^2 / 2 against its motion through the air."""

    coefficient: u.quantity(u.DIMENSIONLESS, ge=0.0) = Field(description="Cd, the drag coefficient")
    area: u.quantity(u.AREA, gt=0.0) = Field(description="A, its cross section")
    air_density: u.quantity(u.DENSITY, gt=0.0) = Field(1.2, description="rho")
    wind: u.quantity(u.VELOCITY) = Field(0.0, description="the wind's velocity along the line")


class VehicleSpec(Section):
    """A mass driven as a vehicle (Modelica's Translational.Components.Vehicle, whose wheel is a gear stage with a
    radius and whose drive train's inertia is a shaft's): its driving resistances, each a force on the mass (N,
    positive in the line's sense) and a term of the ledger.  Rolling: Cr m g cos(alpha) against the motion, grown
    linearly from zero below ``rolling_regularization`` (Modelica's linear regularization); drag: the air's; grade:
    -m g sin(alpha), alpha = atan(inclination), m the mass's and g the scene's ``gravity``.  It writes
    ``<name>_rolling_force``, ``<name>_drag_force`` and ``<name>_grade_force``."""

    mass: Text = Field(description="the mass that is the vehicle's body")
    rolling_resistance: u.quantity(u.DIMENSIONLESS, ge=0.0) = Field(0.0, description="Cr, the rolling resistance's "
                                                                    "coefficient")
    rolling_regularization: u.quantity(u.VELOCITY, gt=0.0) = Field(1e-3, description="the speed below which the "
                                                                   "rolling resistance falls linearly to zero at "
                                                                   "rest (Modelica's vReg)")
    drag: DragSpec | None = Field(None, description="the air's drag (absent: none)")
    inclination: signal(u.DIMENSIONLESS) | None = Field(None, description="tan(alpha), the grade, rising in the "
                                                        "line's positive sense: a signal of time (absent: level)")
    name: str = Field("", exclude=True)  # its key in drivetrain.vehicles (set there, never written)

    def lowered(self, scenario) -> "VehicleSpec":
        """With its weight written in: the mass's m times the scene's gravity (N)."""
        masses = scenario.drivetrain.masses
        return self.with_resolved(weight=masses[self.mass].mass * scenario.gravity)

    def check_mass(self, masses: dict) -> None:
        """Its mass is a mass of the drivetrain."""
        if self.mass not in masses:
            raise ScenarioError(f"drivetrain.vehicles.{self.name}.mass", f"there is no mass {self.mass!r} (masses: "
                                f"{', '.join(masses) or 'none'})")

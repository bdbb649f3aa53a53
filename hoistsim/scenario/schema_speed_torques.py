"""The schema of torques that follow a shaft's speed (values in SI): a torque entry's table of its shaft's speed
or quadratic law (Modelica's QuadraticSpeedDependentTorque), an eddy-current brake (Modelica's
EddyCurrentTorque) and the heat capacitor its heat warms (Modelica's HeatCapacitor), and the quadratic drag of
a load on a level path (Modelica's QuadraticSpeedDependentForce).
"""

from __future__ import annotations

from typing import ClassVar, Literal

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import tables
from . import units as u
from .schema_base import Section
from .schema_masses import LineKeys
from .signals import TimeSignal, signal
from .units import Dimension, Text

SPEED = Dimension("speed", "m/s", "'5 m/s'")
TEMPERATURE_COEFFICIENT = Dimension("temperature coefficient", "1/K", "'3.92e-3 1/K'")
# Modelica's alpha20 is given at 20 degC (Modelica.Electrical.Machines.Thermal.convertAlpha)
ALPHA_TEMPERATURE = 293.15  # K

SPEED_PARTS = ("eddy_current_brakes", "heat_capacitors")  # the drivetrain's keys of these kinds


class QuadraticSpeedSpec(Section):
    """tau = nominal_torque (w / nominal_speed)^2, times sign(w) where the torque's direction ``reverses`` with
    the turning (Modelica's TorqueDirection = false), or the same both ways where ``fixed`` (TorqueDirection =
    true); positive in the shaft's positive sense, so a negative nominal_torque resists turning forwards."""

    nominal_torque: u.quantity(u.TORQUE) = Field(description="tau at nominal_speed (negative: it resists turning "
                                                 "forwards)")
    nominal_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) = Field(description="where the torque is nominal_torque")
    direction: Literal["reverses", "fixed"] = Field("reverses", description="reverses: times sign(w); fixed: the "
                                                    "same whichever way it turns")


class LinearSpeedSpec(Section):
    """tau = nominal_torque w / nominal_speed, its direction reversing with the turning (Modelica's
    LinearSpeedDependentTorque, TorqueDirection = false), or nominal_torque |w| / nominal_speed the same both
    ways where ``fixed`` (TorqueDirection = true); positive in the shaft's positive sense."""

    nominal_torque: u.quantity(u.TORQUE) = Field(description="tau at nominal_speed (negative: it resists turning "
                                                 "forwards)")
    nominal_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) = Field(description="where the torque is nominal_torque")
    direction: Literal["reverses", "fixed"] = Field("reverses", description="reverses: times w's sign, a damper; "
                                                    "fixed: the same whichever way it turns")


class SpeedLaws(Section):
    """A torque entry's laws of its shaft's speed, each in place of ``torque`` (a signal of time): a table
    ``torque_by_speed`` [[speed, torque], ...] (speeds rising; piecewise linear, held beyond its ends) or
    ``quadratic`` or ``linear``."""

    alternatives = (("torque", "torque_by_speed", "quadratic", "linear"),)
    torque_by_speed: tables.TorqueSpeedTable | None = Field(None, description="a law of its shaft's speed, "
                                                            "piecewise linear, held beyond its ends")
    quadratic: QuadraticSpeedSpec | None = Field(None, description="tau = nominal_torque (w / nominal_speed)^2")
    linear: LinearSpeedSpec | None = Field(None, description="tau = nominal_torque w / nominal_speed")

    @model_validator(mode="after")
    def _one_law(self):
        given = [key for key in ("torque", "torque_by_speed", "quadratic", "linear") if getattr(self, key) is not None]
        if len(given) != 1:
            raise ScenarioError(f".{given[1] if given else 'torque'}", "give one of torque (a signal of time), "
                                "torque_by_speed (a table [[speed, torque], ...]), quadratic or linear "
                                "{nominal_torque, nominal_speed}" + (", not both" if given else ""))
        return self

    @property
    def characteristic(self) -> str:
        """Which variant: ``time`` (a signal), ``speed_table``, ``quadratic`` or ``linear``."""
        if self.torque_by_speed is not None:
            return "speed_table"
        return "quadratic" if self.quadratic else "linear" if self.linear else "time"


class HeatCapacitorSpec(Section):
    """A lumped heat capacity (Modelica's HeatCapacitor): C dT/dt = the heat flowing in."""

    heat_capacity: u.quantity(u.HEAT_CAPACITY, gt=0.0) = Field(description="C")
    temperature: u.quantity(u.TEMPERATURE, gt=0.0) = Field(293.15, description="at t = 0")
    name: str = Field("", exclude=True)  # its key in drivetrain.heat_capacitors (set there, never written)

    def lowered(self, scenario) -> "HeatCapacitorSpec":
        """With the eddy-current brake whose heat warms it written in (the schema says there is one)."""
        brakes = scenario.drivetrain.eddy_current_brakes
        return self.with_resolved(brake=next(b for b in brakes.values() if b.heat_to == self.name).lowered(scenario))


class EddyCurrentBrakeSpec(Section):
    """Modelica's EddyCurrentTorque on a shaft: it brakes with 2 nominal_torque e^2 w_n / (1 + w_n^2), w_n =
    w / (nominal_speed (1 + alpha (T - reference_temperature))), e the excitation (a signal of time) and alpha the
    temperature coefficient at 20 degC converted to the reference temperature; its heat goes into a heat capacitor
    (``heat_to``), whose temperature is T, or T is ``temperature``."""

    alternatives = (("heat_to", "temperature"), ("nominal_torque + nominal_speed", "nominal_force + nominal_velocity"))
    line_keys: ClassVar[LineKeys] = LineKeys("shaft", line_only=("nominal_force", "nominal_velocity"),
                                             shafts_only=("nominal_torque", "nominal_speed"))
    shaft: Text = Field(description="the shaft (or the mass) it brakes")
    nominal_torque: u.quantity(u.TORQUE, gt=0.0) | None = Field(None, description="the most it brakes, at "
                                                                "nominal_speed")
    nominal_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) | None = Field(None, description="where it brakes most, at "
                                                                      "reference_temperature")
    nominal_force: u.quantity(u.FORCE, gt=0.0) | None = Field(None, description="on a mass (Modelica's "
                                                              "EddyCurrentForce): the most it brakes, at "
                                                              "nominal_velocity")
    nominal_velocity: u.quantity(u.VELOCITY, gt=0.0) | None = Field(None, description="on a mass: where it brakes "
                                                                    "most, at reference_temperature")
    excitation: signal(u.DIMENSIONLESS) = Field(TimeSignal(times=(0.0,), values=(1.0,)), description="e (1: the "
                                                "nominal torque)")
    temperature_coefficient: u.quantity(TEMPERATURE_COEFFICIENT) = Field(0.0, description="alpha20, the disc's "
                                                                         "resistance's, at 20 degC")
    reference_temperature: u.quantity(u.TEMPERATURE, gt=0.0) = Field(293.15, description="where nominal_speed "
                                                                     "holds")
    heat_to: Text | None = Field(None, description="the heat capacitor its heat warms, whose temperature it has")
    temperature: u.quantity(u.TEMPERATURE, gt=0.0) | None = Field(None, description="a constant temperature, "
                                                                  "without heat_to (default: the reference)")
    name: str = Field("", exclude=True)  # its key in drivetrain.eddy_current_brakes (set there, never written)

    @model_validator(mode="after")
    def _heat_to_or_temperature(self):
        # on a shaft its torque and speed, on a mass its force and velocity: the same law in the line's units
        line = (self.nominal_force, self.nominal_velocity)
        if None not in line and self.nominal_torque is None and self.nominal_speed is None:
            self._derive("nominal_torque", self.nominal_force)
            self._derive("nominal_speed", self.nominal_velocity)
        elif self.nominal_torque is None or self.nominal_speed is None or line != (None, None):
            given = [key for key in ("nominal_torque", "nominal_speed", "nominal_force", "nominal_velocity")
                     if getattr(self, key) is not None]
            raise ScenarioError(f".{'nominal_torque' if not given else given[-1]}", "give nominal_torque and "
                                "nominal_speed (on a shaft), or nominal_force and nominal_velocity (on a mass)")
        if self.heat_to is not None and self.temperature is not None:
            raise ScenarioError(".temperature", "give either heat_to (a heat capacitor, whose temperature the brake "
                                "has) or temperature (a constant), not both")
        return self

    def lowered(self, scenario) -> "EddyCurrentBrakeSpec":
        """With whether it brakes a mass written in (``on_line``)."""
        return self.with_resolved(on_line=self.shaft in scenario.drivetrain.masses)

    def alpha_at_reference(self) -> float:
        """1/K: the temperature coefficient at the reference temperature (Modelica's convertAlpha)."""
        alpha = self.temperature_coefficient
        return alpha / (1.0 + alpha * (self.reference_temperature - ALPHA_TEMPERATURE))


class DragSpec(Section):
    """A force resisting the load's motion along its path, quadratic in its speed: force (v / speed)^2 against
    v (Modelica's QuadraticSpeedDependentForce with f_nominal = -force, ForceDirection = false)."""

    force: u.quantity(u.FORCE, ge=0.0) = Field(description="the drag at speed")
    speed: u.quantity(SPEED, gt=0.0) = Field(description="where the drag is force")


def check_speed_parts(drivetrain, names_taken: set, is_name) -> None:
    """Each eddy-current brake names a shaft there is and a heat capacitor there is, no capacitor takes two
    brakes' heat and each takes one's; names are words (``is_name``, the drivetrain's rule) not taken by another
    part (``names_taken``)."""
    for kind in SPEED_PARTS:
        for name in getattr(drivetrain, kind):
            if not is_name(name) or name in names_taken:
                raise ScenarioError(f"drivetrain.{kind}.{name}", "a name is a word of letters, digits and "
                                    "underscores starting with a letter, not 'ground' and not the name of "
                                    "another part (they name the outputs)")
            names_taken.add(name)
    heated: dict = {}
    for name, brake in drivetrain.eddy_current_brakes.items():
        if brake.shaft not in drivetrain.shafts and brake.shaft not in drivetrain.masses:
            raise ScenarioError(f"drivetrain.eddy_current_brakes.{name}.shaft", f"there is no shaft {brake.shaft!r} "
                                f"(shafts: {', '.join(drivetrain.shafts)}; masses: "
                                f"{', '.join(drivetrain.masses) or 'none'})")
        if brake.heat_to is None:
            continue
        if brake.heat_to not in drivetrain.heat_capacitors:
            known = ", ".join(drivetrain.heat_capacitors) or "none"
            raise ScenarioError(f"drivetrain.eddy_current_brakes.{name}.heat_to", f"there is no heat capacitor "
                                f"{brake.heat_to!r} (drivetrain.heat_capacitors: {known})")
        if brake.heat_to in heated:
            raise ScenarioError(f"drivetrain.eddy_current_brakes.{name}.heat_to", f"heat capacitor "
                                f"{brake.heat_to!r} already takes brake {heated[brake.heat_to]!r}'s heat: give "
                                "each brake a capacitor of its own")
        heated[brake.heat_to] = name
    for name in drivetrain.heat_capacitors:
        if name not in heated:
            raise ScenarioError(f"drivetrain.heat_capacitors.{name}", "no eddy-current brake puts its heat into it "
                                "(give a brake heat_to: " + name + ")")

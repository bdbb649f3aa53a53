"""The schema of a motor (``motor:``, and a drawn drivetrain's ``motors:``) and of a torque periodic in an
angle (a motor's or a drum's ``ripple``), values in SI."""

from __future__ import annotations

import math
from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import tables
from . import units as u
from .schema_base import Section


class HarmonicSpec(Section):
    """One harmonic of a ripple: amplitude * sin(order * 2 pi * angle / period + phase)."""

    order: u.whole("periods per ripple period") = Field(description="k: its periods in one period of the ripple")
    amplitude: u.quantity(u.TORQUE) = Field(description="its torque's amplitude")
    phase: u.quantity(u.ANGLE) = Field(0.0, description="its phase at angle 0")


class RippleSpec(Section):
    """A torque periodic in a shaft's angle: harmonics, or one period as a table (not both)."""

    alternatives = (("harmonics", "table"),)
    period: u.quantity(u.ANGLE, gt=0.0) = Field(2 * math.pi, description="the angle it repeats over (720 deg for "
                                                "a four-stroke engine)")
    harmonics: list[HarmonicSpec] | None = Field(None, description="summed")
    table: tables.AngleTorqueTable | None = Field(None, description="one period, from 0 to the period, piecewise "
                                                  "linear, ending where it starts")

    @model_validator(mode="after")
    def _one_form(self):
        if self.harmonics is not None and self.table is not None:
            raise ScenarioError(".table", "give either harmonics or a table, not both")
        if self.harmonics is None and self.table is None:
            raise ScenarioError(".harmonics", "required: harmonics (order, amplitude, phase) or a table of one period")
        if self.harmonics is not None and not self.harmonics:
            raise ScenarioError(".harmonics", "give at least one harmonic {order, amplitude, phase}")
        if self.table is not None:
            first, last = self.table[0], self.table[-1]
            if first[0] != 0.0 or not math.isclose(last[0], self.period, rel_tol=1e-12):
                raise ScenarioError(".table", f"must span exactly one period, from 0 to {math.degrees(self.period):g} deg "
                                    f"(got {math.degrees(first[0]):g} to {math.degrees(last[0]):g} deg)")
            if first[1] != last[1]:
                raise ScenarioError(".table", f"must end where it starts, one period on ({first[1]:g} N*m at 0, "
                                    f"{last[1]:g} N*m at the end)")
        return self


class MotorSpec(Section):
    """A motor: one characteristic (its torque against its speed) and its rotor's inertia."""

    # exactly one characteristic: linear (C0 and omega0), a torque-speed table, or a constant torque
    alternatives = (("stall_torque + no_load_speed", "torque_speed", "torque"),
                              ("inertia", "rotor_mass + radius_of_gyration"))
    stall_torque: u.quantity(u.TORQUE, gt=0.0) | None = Field(None, description="C0, the torque at standstill "
                                                              "(linear: C = C0 (1 - omega / omega0))")
    no_load_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) | None = Field(None, description="omega0, where the linear "
                                                                      "torque reaches 0")
    torque_speed: tables.TorqueSpeedTable | None = Field(None, description="the characteristic as a table, linear "
                                                         "between rows and beyond its ends")
    torque: u.quantity(u.TORQUE) | None = Field(None, description="a constant torque (0 N*m: the motor is off, its "
                                                "shaft coasts)")
    inertia: u.quantity(u.INERTIA, gt=0.0) | None = Field(None, description="the rotor's")
    rotor_mass: u.quantity(u.MASS, gt=0.0) | None = Field(None, description="the rotor's mass (I = m k^2)")
    radius_of_gyration: u.quantity(u.LENGTH, gt=0.0) | None = Field(None, description="the rotor's, k")
    ripple: RippleSpec | None = Field(None, description="a torque added to the characteristic, periodic in the "
                                      "motor's angle")

    @model_validator(mode="after")
    def _one_characteristic(self):
        given = [name for name in ("stall_torque", "no_load_speed", "torque_speed", "torque")
                 if getattr(self, name) is not None]
        linear = {"stall_torque", "no_load_speed"} & set(given)
        others = [name for name in given if name not in linear]
        if linear and others:
            raise ScenarioError(f".{others[0]}", "give one characteristic: stall_torque + no_load_speed "
                                f"(linear), torque_speed (a table) or torque (constant); got {', '.join(given)}")
        if len(others) > 1:
            raise ScenarioError(f".{others[1]}", "give one characteristic: stall_torque + no_load_speed "
                                f"(linear), torque_speed (a table) or torque (constant); got {', '.join(given)}")
        if not given:
            raise ScenarioError(".stall_torque", "required: a characteristic, stall_torque + no_load_speed "
                                "(linear), torque_speed (a table) or torque (constant)")
        if linear and len(linear) == 1:
            missing = ".no_load_speed" if self.no_load_speed is None else ".stall_torque"
            raise ScenarioError(missing, "required with a linear characteristic (stall_torque + no_load_speed)")
        return self

    @property
    def characteristic(self) -> str:
        """Which variant: ``linear``, ``torque_speed`` or ``torque``."""
        if self.torque_speed is not None:
            return "torque_speed"
        return "torque" if self.torque is not None else "linear"

    @model_validator(mode="after")
    def _one_inertia(self):
        by_geometry = self.rotor_mass is not None or self.radius_of_gyration is not None
        if self.inertia is not None and by_geometry:
            raise ScenarioError(".inertia", "give either inertia or rotor_mass + radius_of_gyration, not both")
        if self.inertia is None and not (self.rotor_mass is not None and self.radius_of_gyration is not None):
            missing = ".inertia" if not by_geometry else (
                ".radius_of_gyration" if self.rotor_mass is not None else ".rotor_mass")
            raise ScenarioError(missing, "required: the motor's inertia, or its rotor_mass and radius_of_gyration")
        return self

    @property
    def moment_of_inertia(self) -> float:
        if self.inertia is not None:
            return self.inertia
        return self.rotor_mass * self.radius_of_gyration**2

"""The schema of a motor (``motor:``, and a drawn drivetrain's ``motors:``) and of a torque periodic in an
angle (a motor's or a drum's ``ripple``), values in SI."""

from __future__ import annotations

import math

from pydantic import model_validator

from ..errors import ScenarioError
from . import tables
from . import units as u
from .schema_base import Section


class HarmonicSpec(Section):
    order: u.whole("periods per ripple period")  # k: amplitude * sin(k * 2 pi * angle / period + phase)
    amplitude: u.quantity(u.TORQUE)
    phase: u.quantity(u.ANGLE) = 0.0


class RippleSpec(Section):
    """A torque periodic in a shaft's angle: harmonics, or one period as a table (not both)."""

    period: u.quantity(u.ANGLE, gt=0.0) = 2 * math.pi
    harmonics: list[HarmonicSpec] | None = None
    table: tables.AngleTorqueTable | None = None

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
    # exactly one characteristic: linear (C0 and omega0), a torque-speed table, or a constant torque
    stall_torque: u.quantity(u.TORQUE, gt=0.0) | None = None  # C0, torque at standstill
    no_load_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) | None = None  # omega0, where the torque reaches 0
    torque_speed: tables.TorqueSpeedTable | None = None
    torque: u.quantity(u.TORQUE) | None = None  # 0 N*m: the motor is off and its shaft coasts
    inertia: u.quantity(u.INERTIA, gt=0.0) | None = None
    rotor_mass: u.quantity(u.MASS, gt=0.0) | None = None
    radius_of_gyration: u.quantity(u.LENGTH, gt=0.0) | None = None
    ripple: RippleSpec | None = None  # a torque added to the characteristic, periodic in the motor angle

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

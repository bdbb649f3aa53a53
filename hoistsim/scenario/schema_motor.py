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


# the characteristics a motor may have, as its keys name them
_FORMS = ("stall_torque + no_load_speed (linear), or rated_power + rated_speed + no_load_speed (the line through "
          "the rated point); breakdown_torque + breakdown_slip + no_load_speed (Kloss), or breakdown_torque + "
          "rated_power + rated_speed + no_load_speed; torque_speed (a table); or torque (constant)")


class MotorSpec(Section):
    # exactly one characteristic: linear (C0 and omega0, or the nameplate's rated power and speed with omega0), an
    # induction motor's Kloss curve (its breakdown torque, and its breakdown slip or its rated point), a
    # torque-speed table, or a constant torque
    stall_torque: u.quantity(u.TORQUE, gt=0.0) | None = None  # C0, torque at standstill
    # omega0, where the torque reaches 0 (an induction motor's synchronous speed)
    no_load_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) | None = None
    rated_power: u.quantity(u.POWER, gt=0.0) | None = None  # P_N, the nameplate's, at rated_speed
    rated_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) | None = None  # n_N, below no_load_speed
    breakdown_torque: u.quantity(u.TORQUE, gt=0.0) | None = None  # T_b, the most an induction motor gives (Kloss)
    breakdown_slip: u.quantity(u.DIMENSIONLESS, gt=0.0, le=1.0) | None = None  # s_b, where it gives it
    torque_speed: tables.TorqueSpeedTable | None = None
    torque: u.quantity(u.TORQUE) | None = None  # 0 N*m: the motor is off and its shaft coasts
    inertia: u.quantity(u.INERTIA, gt=0.0) | None = None
    rotor_mass: u.quantity(u.MASS, gt=0.0) | None = None
    radius_of_gyration: u.quantity(u.LENGTH, gt=0.0) | None = None
    ripple: RippleSpec | None = None  # a torque added to the characteristic, periodic in the motor angle

    @model_validator(mode="after")
    def _one_characteristic(self):
        forms = {"linear": ("stall_torque", "rated_power", "rated_speed", "no_load_speed"),
                 "kloss": ("breakdown_torque", "breakdown_slip", "rated_power", "rated_speed", "no_load_speed")}
        given = [name for name in ("stall_torque", "rated_power", "rated_speed", "breakdown_torque", "breakdown_slip",
                                   "no_load_speed", "torque_speed", "torque") if getattr(self, name) is not None]
        kind = ("kloss" if self.breakdown_torque is not None or self.breakdown_slip is not None
                else "torque_speed" if self.torque_speed is not None else "torque" if self.torque is not None
                else "linear")
        allowed = forms.get(kind, (kind,))
        stray = [name for name in given if name not in allowed]
        if stray:
            raise ScenarioError(f".{stray[0]}", f"give one characteristic: {_FORMS}; got {', '.join(given)}")
        if not given:
            raise ScenarioError(".stall_torque", f"required: a characteristic, {_FORMS}")
        if kind == "linear":
            self._linear_from_nameplate()
        if kind == "kloss":
            self._kloss_from_nameplate()
        return self

    def _rated_point(self, form: str) -> tuple[float, float] | None:
        """(rated torque P_N / n_N, rated slip (omega0 - n_N) / omega0), or None where no rated point is given."""
        if self.rated_power is None and self.rated_speed is None:
            return None
        for key in ("rated_power", "rated_speed", "no_load_speed"):
            if getattr(self, key) is None:
                raise ScenarioError(f".{key}", f"required with {form}: rated_power, rated_speed and no_load_speed")
        if self.rated_speed >= self.no_load_speed:
            raise ScenarioError(".rated_speed", f"must be below no_load_speed ({u.show(self.no_load_speed, u.ANGULAR_SPEED)}),"
                                f" got {u.show(self.rated_speed, u.ANGULAR_SPEED)}: a motor gives its rated power "
                                "while it slips")
        return self.rated_power / self.rated_speed, 1.0 - self.rated_speed / self.no_load_speed

    def _linear_from_nameplate(self):
        rated = self._rated_point("a linear characteristic from the nameplate")
        if rated is None:
            if (self.stall_torque is None) != (self.no_load_speed is None):
                missing = ".no_load_speed" if self.no_load_speed is None else ".stall_torque"
                raise ScenarioError(missing, "required with a linear characteristic (stall_torque + no_load_speed)")
            return
        if self.stall_torque is not None:
            raise ScenarioError(".stall_torque", "give either stall_torque or the nameplate's rated_power and "
                                "rated_speed, not both")
        torque, slip = rated
        # the line through the rated point reaching zero at omega0: C0 = T_N / s_N
        self._derive("stall_torque", torque / slip)

    def _kloss_from_nameplate(self):
        if self.breakdown_torque is None:
            raise ScenarioError(".breakdown_torque", "required with breakdown_slip (Kloss's curve of an induction "
                                "motor: breakdown_torque, breakdown_slip and no_load_speed, its synchronous speed)")
        rated = self._rated_point("Kloss's curve from the nameplate")
        if rated is None:
            for key in ("breakdown_slip", "no_load_speed"):
                if getattr(self, key) is None:
                    raise ScenarioError(f".{key}", "required with breakdown_torque (Kloss's curve: breakdown_torque, "
                                        "breakdown_slip and no_load_speed, or rated_power and rated_speed for the "
                                        "slip)")
            return
        if self.breakdown_slip is not None:
            raise ScenarioError(".breakdown_slip", "give either breakdown_slip or the rated point it follows from "
                                "(rated_power, rated_speed), not both")
        torque, slip = rated
        ratio = self.breakdown_torque / torque
        if ratio <= 1.0:
            raise ScenarioError(".breakdown_torque", f"must exceed the rated torque P_N / n_N ({torque:.6g} N*m), got "
                                f"{self.breakdown_torque:.6g} N*m")
        # Kloss at the rated point, T_N / T_b = 2 / (s_N / s_b + s_b / s_N): the root on the working branch
        breakdown = slip * (ratio + math.sqrt(ratio**2 - 1.0))
        if breakdown > 1.0:
            raise ScenarioError(".breakdown_torque", f"puts the breakdown slip at {breakdown:.4g}, beyond standstill "
                                "(above 1): the rated point and breakdown torque do not make an induction motor's curve")
        self._derive("breakdown_slip", breakdown)

    @property
    def characteristic(self) -> str:
        """Which variant: ``linear``, ``kloss``, ``torque_speed`` or ``torque``."""
        if self.breakdown_torque is not None:
            return "kloss"
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

"""The schema of a motor (``motor:``, and a drawn drivetrain's ``motors:``) and of a torque periodic in an
angle (a motor's or a drum's ``ripple``), values in SI."""

from __future__ import annotations

import math
from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import tables
from . import plausible
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


# the characteristics a motor may have, as its keys name them
_FORMS = ("stall_torque + no_load_speed (linear), or rated_power + rated_speed + no_load_speed (the line through "
          "the rated point); breakdown_torque + breakdown_slip + no_load_speed (Kloss), or breakdown_torque + "
          "rated_power + rated_speed + no_load_speed; torque_speed (a table); or torque (constant)")


class MotorSpec(Section):
    """A motor: one characteristic (its torque against its speed) and its rotor's inertia."""

    # exactly one characteristic: linear (C0 and omega0, or the nameplate's rated power and speed with omega0), an
    # induction motor's Kloss curve (its breakdown torque, and its breakdown slip or its rated point), a
    # torque-speed table, or a constant torque
    alternatives = (("stall_torque + no_load_speed", "rated_power + rated_speed + no_load_speed",
                     "breakdown_torque + breakdown_slip + no_load_speed",
                     "breakdown_torque + rated_power + rated_speed + no_load_speed", "torque_speed", "torque"),
                    ("inertia", "rotor_mass + radius_of_gyration"))
    stall_torque: u.quantity(u.TORQUE, gt=0.0) | None = Field(None, description="C0, the torque at standstill "
                                                              "(linear: C = C0 (1 - omega / omega0))")
    no_load_speed: u.quantity(u.ANGULAR_SPEED, plausible=plausible.MOTOR_SPEED, gt=0.0) | None = Field(
        None, description="omega0, where the torque reaches 0 (an induction motor's synchronous speed)")
    rated_power: u.quantity(u.POWER, gt=0.0) | None = Field(None, description="P_N, the nameplate's, at rated_speed: "
                                                            "the line through the rated point, C0 = T_N / s_N")
    rated_speed: u.quantity(u.ANGULAR_SPEED, plausible=plausible.MOTOR_SPEED, gt=0.0) | None = Field(
        None, description="n_N, the nameplate's, below no_load_speed")
    breakdown_torque: u.quantity(u.TORQUE, gt=0.0) | None = Field(None, description="T_b, an induction motor's "
                                                                  "greatest torque (Kloss: T = 2 T_b / (s / s_b + "
                                                                  "s_b / s))")
    breakdown_slip: u.quantity(u.DIMENSIONLESS, gt=0.0, le=1.0) | None = Field(
        None, description="s_b, the slip (1 - omega / omega0) where it gives T_b; or from the rated point")
    torque_speed: tables.TorqueSpeedTable | None = Field(None, description="the characteristic as a table, linear "
                                                         "between rows and beyond its ends")
    torque: u.quantity(u.TORQUE) | None = Field(None, description="a constant torque (0 N*m: the motor is off, its "
                                                "shaft coasts)")
    inertia: u.quantity(u.INERTIA, gt=0.0) | None = Field(None, description="the rotor's")
    rotor_mass: u.quantity(u.MASS, gt=0.0) | None = Field(None, description="the rotor's mass (I = m k^2)")
    radius_of_gyration: u.quantity(u.LENGTH, plausible=plausible.ROTOR_RADIUS_OF_GYRATION, gt=0.0) | None = Field(
        None, description="the rotor's, k")
    ripple: RippleSpec | None = Field(None, description="a torque added to the characteristic, periodic in the "
                                      "motor's angle")

    @model_validator(mode="after")
    def _one_characteristic(self):
        forms = {"linear": ("stall_torque", "rated_power", "rated_speed", "no_load_speed"),
                 "kloss": ("breakdown_torque", "breakdown_slip", "rated_power", "rated_speed", "no_load_speed")}
        given = [name for name in ("stall_torque", "rated_power", "rated_speed", "breakdown_torque", "breakdown_slip",
                                   "no_load_speed", "torque_speed", "torque") if getattr(self, name) is not None]
        # the form its keys point to, a linear one before a table or a constant (the other keys are the strays)
        kind = ("kloss" if self.breakdown_torque is not None or self.breakdown_slip is not None
                else "linear" if set(given) & set(forms["linear"])
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

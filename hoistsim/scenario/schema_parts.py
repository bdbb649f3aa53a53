"""The keys of the parts the hoist's sections and a drawn drivetrain share: a rotor (flywheel), a slider-crank,
a brake, a ratchet and a clutch's heating (values in SI).  The hoist's section of each is these keys on its
template's shaft; a drawn drivetrain's adds the shaft it sits on (:mod:`.schema_drawn_parts`)."""

from __future__ import annotations

import math
from typing import Literal

import numpy as np
from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import tables
from . import plausible
from . import units as u
from .schema_base import Section


class FlywheelSpec(Section):
    """An inertia keyed to a shaft: given as such, or a rim's, I = pi density width (R_outer^4 - R_inner^4) / 2."""

    alternatives = (("inertia", "density + outer_diameter + inner_diameter + width"),)
    shaft: Literal["motor", "drum"] = Field("motor", description="the shaft it is keyed to")
    inertia: u.quantity(u.INERTIA, ge=0.0) | None = Field(None, description="its moment of inertia")
    # or a rim: I = pi * density * width * (R_outer^4 - R_inner^4) / 2
    density: u.quantity(u.DENSITY, gt=0.0) | None = Field(None, description="the rim's material's")
    outer_diameter: u.quantity(u.LENGTH, plausible=plausible.FLYWHEEL_RIM_DIAMETER, gt=0.0) | None = Field(
        None, description="the rim's")
    inner_diameter: u.quantity(u.LENGTH, plausible=plausible.FLYWHEEL_RIM_DIAMETER, ge=0.0) | None = Field(
        None, description="the rim's bore (less than outer_diameter)")
    width: u.quantity(u.LENGTH, plausible=plausible.FLYWHEEL_RIM_WIDTH, gt=0.0) | None = Field(
        None, description="the rim's, along the shaft")

    @model_validator(mode="after")
    def _inertia_or_rim(self):
        rim = self._one_value_or_group(
            "", "inertia", ("density", "outer_diameter", "inner_diameter", "width"),
            both="inertia or a rim (density, outer_diameter, inner_diameter, width)",
            required="the flywheel's inertia, or a rim's density, outer_diameter, inner_diameter and width")
        if rim and self.inner_diameter >= self.outer_diameter:
            raise ScenarioError(".inner_diameter", f"must be less than outer_diameter "
                                f"({self.outer_diameter:g} m), got {self.inner_diameter:g} m")
        return self

    @property
    def moment_of_inertia(self) -> float:
        """kg*m^2: as given, or the rim's pi rho s (R_o^4 - R_i^4) / 2."""
        if self.inertia is not None:
            return self.inertia
        outer, inner = 0.5 * self.outer_diameter, 0.5 * self.inner_diameter
        return math.pi * self.density * self.width * (outer**4 - inner**4) / 2.0


class ReciprocatingSpec(Section):
    """A slider-crank (on the motor shaft, the hoist's): its reciprocating mass has an inertia that varies with angle."""

    mass: u.quantity(u.MASS, gt=0.0) = Field(description="the reciprocating mass: I = mass (dx/dangle)^2")
    crank_radius: u.quantity(u.LENGTH, plausible=plausible.CRANK_RADIUS, gt=0.0) = Field(description="r")
    rod_length: u.quantity(u.LENGTH, plausible=plausible.CONNECTING_ROD_LENGTH, gt=0.0) = Field(
        description="l, longer than the crank")

    @model_validator(mode="after")
    def _rod_longer_than_crank(self):
        if self.rod_length <= self.crank_radius:
            raise ScenarioError(".rod_length", f"must be longer than the crank ({self.crank_radius:g} m), "
                                f"got {self.rod_length:g} m: the rod could not follow the crank")
        return self


class BrakeSpec(Section):
    """A brake holding its shaft (the hoist's: the drum) until its release: any torque, or up to a static torque."""

    release_time: u.quantity(u.TIME, ge=0.0) = Field(description="the brake frees its shaft at this time")
    static_torque: u.quantity(u.TORQUE, gt=0.0) | None = Field(None, description="the most it holds (absent: any, "
                                                               "never slipping)")
    kinetic_torque: u.quantity(u.TORQUE, ge=0.0) | None = Field(None, description="what it passes slipping "
                                                                "(default: static_torque)")
    apply_time: u.quantity(u.TIME, ge=0.0) | None = Field(None, description="it closes again at this time (with "
                                                          "static_torque)")

    @model_validator(mode="after")
    def _consistent(self):
        if self.kinetic_torque is not None and self.static_torque is None:
            raise ScenarioError(".kinetic_torque", "needs static_torque (a brake without it holds any torque "
                                "and never slips)")
        if self.kinetic_torque is not None and self.kinetic_torque > self.static_torque:
            raise ScenarioError(".kinetic_torque", f"must not exceed static_torque ({self.static_torque:g} "
                                f"N*m), got {self.kinetic_torque:g} N*m")
        if self.apply_time is not None and self.release_time is not None and self.apply_time <= self.release_time:
            raise ScenarioError(".apply_time", f"must be after release_time ({self.release_time:g} s), "
                                f"got {self.apply_time:g} s")
        if self.apply_time is not None and self.static_torque is None:
            raise ScenarioError(".apply_time", "needs static_torque: a brake that holds any torque would "
                                "stop a turning drum dead")
        return self

    @property
    def characteristic(self) -> str:
        """Which variant: ``holding`` (any torque, never slips) or ``friction`` (slips above static_torque)."""
        return "holding" if self.static_torque is None else "friction"


class RatchetSpec(Section):
    """A pawl: its shaft (the hoist's: the drum) may turn forwards (to lift), never back, until it is lifted."""

    release_time: u.quantity(u.TIME, ge=0.0) | None = Field(None, description="the pawl is lifted at this time "
                                                            "(absent: never)")


class ClutchHeatingSpec(Section):
    """The clutch's friction surfaces as one lump of heat: C dT/dt = slip power - G (T - T_ambient)."""

    heat_capacity: u.quantity(u.HEAT_CAPACITY, gt=0.0) = Field(description="C, of the friction surfaces")
    cooling: u.quantity(u.CONDUCTANCE, " (the conductance to ambient)", ge=0.0) = Field(
        description="G, the conductance to ambient (0: none)")
    ambient_temperature: u.quantity(u.TEMPERATURE, gt=0.0) = Field(description="T_ambient")
    initial_temperature: u.quantity(u.TEMPERATURE, gt=0.0) | None = Field(None, description="at t = 0 (default: "
                                                                          "ambient)")
    # friction against temperature, replacing clutch.static_friction / kinetic_friction where given
    static_friction: tables.StaticFrictionTable | None = Field(None, description="in place of the clutch's, linear "
                                                               "between rows, flat beyond")
    kinetic_friction: tables.KineticFrictionTable | None = Field(None, description="in place of the clutch's, "
                                                                 "linear between rows, flat beyond")
    max_temperature: u.quantity(u.TEMPERATURE, gt=0.0) | None = Field(None, description="an overheat event where "
                                                                      "it is crossed")

    @property
    def start_temperature(self) -> float:
        return self.ambient_temperature if self.initial_temperature is None else self.initial_temperature

    @property
    def fades(self) -> bool:
        """Whether friction depends on temperature (a table is given)."""
        return self.static_friction is not None or self.kinetic_friction is not None

    @model_validator(mode="after")
    def _limit_above_start(self):
        if self.max_temperature is not None and self.max_temperature <= self.start_temperature:
            raise ScenarioError(".max_temperature", f"must be above the initial temperature "
                                f"({u.show(self.start_temperature, u.TEMPERATURE)}), got "
                                f"{u.show(self.max_temperature, u.TEMPERATURE)}")
        return self


class BearingsSpec(Section):
    """The drum shaft's two bearings, A and B: the tooth forces, the rope's pull and their reactions in time."""

    gear_offset: u.quantity(u.LENGTH, plausible=plausible.DRUM_SHAFT_LENGTHS, gt=0.0) = Field(
        description="a: bearing A to the gear, away from B")
    rope_offset: u.quantity(u.LENGTH, plausible=plausible.DRUM_SHAFT_LENGTHS, gt=0.0) = Field(
        description="bearing A to the rope, towards B")
    span: u.quantity(u.LENGTH, plausible=plausible.DRUM_SHAFT_LENGTHS, gt=0.0) = Field(
        description="bearing A to bearing B")


def kinetic_within_static(heating: ClutchHeatingSpec, static_friction: float, kinetic_friction: float,
                          where: str) -> None:
    """A clutch whose friction fades with its faces' temperature: the kinetic friction must not exceed the static
    at any temperature (the tables replace the clutch's constants where given; ``where``: the heating's key)."""
    if not heating.fades:
        return
    static = heating.static_friction or ((0.0, static_friction),)
    kinetic = heating.kinetic_friction or ((0.0, kinetic_friction),)
    # both piecewise linear, flat beyond their ends: compared at every knot of either, compared everywhere
    given = (heating.static_friction or ()) + (heating.kinetic_friction or ())
    for temperature in sorted({row[0] for row in given}):
        mu_s, mu_k = (float(np.interp(temperature, *zip(*table))) for table in (static, kinetic))
        if mu_k > mu_s:
            # the table that says it: the kinetic one, or the static one that falls below the constant
            key = f"{where}.{'kinetic' if heating.kinetic_friction else 'static'}_friction"
            raise ScenarioError(key, f"the kinetic friction {mu_k:g} is above the static friction {mu_s:g} at "
                                f"{u.show(temperature, u.TEMPERATURE)}; it must not exceed it at any temperature")


def fade_tables(heating, spec) -> dict:
    """The clutch's friction against temperature: its heating's tables (a table not given is the clutch's
    constant), both on the knots of either, which leaves each unchanged (linear between)."""
    given = [table for table in (heating.static_friction, heating.kinetic_friction) if table is not None]
    knots = np.asarray(sorted({row[0] for table in given for row in table}), float)

    def on_knots(table, constant):
        if table is None:
            return np.full(knots.shape, float(constant))
        temperatures, values = (np.asarray(column, float) for column in zip(*table))
        return np.interp(knots, temperatures, values)

    return {"temperatures": knots, "static": on_knots(heating.static_friction, spec.static_friction),
            "kinetic": on_knots(heating.kinetic_friction, spec.kinetic_friction)}

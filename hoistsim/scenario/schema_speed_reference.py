"""A speed controller's reference given as a profile (values in SI): Modelica's KinematicPTP integrated, a
trapezoid or a triangle of speed written as a table of time; a jerk-limited S-curve, whose acceleration is the
table and whose speed the controller integrates.  Either stands where a speed signal would.
"""

from __future__ import annotations

import math
from typing import ClassVar

from pydantic import Field, ValidationError, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .signals import TimeSignal, time_signal
from .units import Dimension

class KinematicPtpSpec(Section):
    """Modelica's KinematicPTP integrated: the speed that moves a shaft through ``distance`` as fast as its
    ``max_speed`` and ``max_acceleration`` let it, from ``start`` (accelerating at the most, at the most speed a
    while where the distance leaves room, decelerating to rest)."""

    distance: u.quantity(u.ANGLE) = Field(description="delta q, the angle to move (negative: backwards)")
    max_speed: u.quantity(u.ANGULAR_SPEED, gt=0.0) = Field(description="qd_max")
    max_acceleration: u.quantity(u.ANGULAR_ACCELERATION, gt=0.0) = Field(description="qdd_max")
    start: u.quantity(u.TIME, ge=0.0) = Field(0.0, description="when it starts moving")

    @model_validator(mode="after")
    def _a_distance(self):
        if self.distance == 0.0:
            raise ScenarioError(".distance", "must not be 0: a profile that moves nothing")
        return self

    def table(self) -> tuple:
        """(times, speeds) of the profile, five rows whatever its shape (a triangle's peak twice)."""
        span, sign = abs(self.distance), math.copysign(1.0, self.distance)
        ramp = self.max_speed / self.max_acceleration  # Ta2: up to the most speed
        shortest = math.sqrt(span / self.max_acceleration)  # Ta1: a triangle's half
        if ramp >= shortest:  # no time at the most speed: a triangle
            up, top, peak = shortest, shortest, self.max_acceleration * shortest
        else:
            up, top, peak = ramp, span / self.max_speed, self.max_speed
        end = top + up
        times = (0.0, self.start, self.start + up, self.start + top, self.start + end)
        return times, (0.0, 0.0, sign * peak, sign * peak, 0.0)


JERK = Dimension("angular jerk", "rad/s^3", "'5 rad/s^3'", radians=1)


class SCurveSpec(Section):
    """A jerk-limited speed profile (an S-curve): from ``start`` the speed rises to ``speed`` with the acceleration
    ramped at ``jerk`` up to ``acceleration`` (less where the speed is reached first), held for ``hold``, and
    brought back to rest the same way.  Its acceleration is piecewise linear in time (a table, its corners
    segment boundaries); the speed is its integral, a state of the controller, exact."""

    speed: u.quantity(u.ANGULAR_SPEED) = Field(description="the cruising speed (negative: backwards)")
    acceleration: u.quantity(u.ANGULAR_ACCELERATION, gt=0.0) = Field(description="the most acceleration")
    jerk: u.quantity(JERK, gt=0.0) = Field(description="the acceleration's most rate of change")
    start: u.quantity(u.TIME, ge=0.0) = Field(0.0, description="when it starts")
    hold: u.quantity(u.TIME, ge=0.0) = Field(0.0, description="how long it cruises at speed")

    def table(self) -> tuple:
        """(times, accelerations): eight rows whatever its shape (a corner twice where no acceleration is held)."""
        size, sign = abs(self.speed), math.copysign(1.0, self.speed)
        peak = min(self.acceleration, math.sqrt(size * self.jerk))  # where the speed comes before the most
        ramp = peak / self.jerk
        held = size / peak - ramp if size > 0 else 0.0
        marks = [0.0, ramp, ramp + held, 2 * ramp + held]
        up = [self.start + m for m in marks]
        down = [up[-1] + self.hold + m for m in marks]
        return tuple(up + down), tuple(sign * a for a in (0.0, peak, peak, 0.0, 0.0, -peak, -peak, 0.0))


class AccelerationSignal(TimeSignal):
    """A speed given by its acceleration (an S-curve's table): the element integrates it, from rest."""

    integrated: ClassVar[bool] = True


def speed_reference(value):
    """A speed reference: any signal of a speed, ``{kinematic_ptp: {...}}`` (:class:`KinematicPtpSpec`) or
    ``{s_curve: {...}}`` (:class:`SCurveSpec`: its acceleration, which the controller integrates)."""
    if isinstance(value, dict) and set(value) == {"s_curve"}:
        try:
            times, accelerations = SCurveSpec.model_validate(value["s_curve"]).table()
            return AccelerationSignal(times=times, values=accelerations)
        except ValidationError as exc:
            error = exc.errors()[0]
            raise u.UnitError(f"s_curve.{'.'.join(str(p) for p in error['loc'])}: "
                              f"{error['msg'].removeprefix('Value error, ')}") from None
    if isinstance(value, dict) and set(value) == {"kinematic_ptp"}:
        try:
            times, speeds = KinematicPtpSpec.model_validate(value["kinematic_ptp"]).table()
        except ValidationError as exc:  # said at the reference's place, its key within it named
            error = exc.errors()[0]
            where, said = ".".join(str(p) for p in error["loc"]), error["msg"].removeprefix("Value error, ")
            if not where and said.startswith("."):  # a check of the profile's own: ".distance: ..."
                where, _, said = said[1:].partition(": ")
            if error["type"] == "extra_forbidden":
                said = "is no key of a profile (distance, max_speed, max_acceleration, start)"
            if error["type"] == "missing":
                said = "is required (a profile has distance, max_speed, max_acceleration and, optional, start)"
            raise u.UnitError(f"kinematic_ptp.{where}: {said}") from None
        except ScenarioError as exc:
            raise u.UnitError(f"kinematic_ptp{exc.key}: {exc.message}") from None
        return TimeSignal(times=times, values=speeds)
    return time_signal(value, u.ANGULAR_SPEED)

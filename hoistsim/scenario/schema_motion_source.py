"""The schema of a prescribed motion (values in SI): a shaft driven at a speed, an angle or an acceleration given
as a signal of time, whatever torque that takes (Modelica's Rotational.Sources Speed, Position and Accelerate).
"""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .schema_masses import LineKeys
from .signals import signal
from .units import Text

MOTIONS = ("speed", "angle", "acceleration", "velocity", "position")  # what a source may prescribe, by its keys
ACCELERATION = u.ANGULAR_ACCELERATION.on_line(u.ACCELERATION)  # a shaft's, or a mass's (m/s^2)


class MotionSourceSpec(Section):
    """A shaft driven to the ground at a prescribed motion: its ``speed``, its ``angle`` or its ``acceleration``, a
    signal of time, one of the three.  It holds the shaft at that motion whatever torque it takes: its output
    ``<name>_torque`` (N*m, what it applies to the shaft, positive in the shaft's positive sense), its work a term
    of the energy ledger.  Exactly (Modelica's ``exact=true``): a speed that steps, or an angle whose table kinks,
    jumps the shaft's speed there, its impulse's work booked to the source.  With ``filter_frequency`` (Modelica's
    ``exact=false``, its ``f_crit``): the shaft follows the reference through a filter, a speed through a first
    order lag, an angle through Modelica's second-order Bessel filter, starting at the reference's
    value (and, for an angle, at rest).  A shaft driven to an angle starts at the reference's angle; one driven at
    an acceleration keeps the speed it starts with and accelerates as told."""

    alternatives = (MOTIONS,)
    line_keys: ClassVar[LineKeys] = LineKeys("shaft", measured=("acceleration",), line_only=("velocity", "position"),
                                             shafts_only=("speed", "angle"))
    shaft: Text = Field(description="the shaft or the mass it drives (its inertia, and what its parts take, are "
                        "the source's torque too)")
    speed: signal(u.ANGULAR_SPEED) | None = Field(None, description="the speed it drives the shaft at: a "
                                                          "signal of time")
    angle: signal(u.ANGLE) | None = Field(None, description="the angle it drives the shaft to: a signal "
                                                  "of time")
    acceleration: signal(ACCELERATION) | None = Field(None, description="the acceleration it drives the shaft "
                                                      "(or mass) at: a signal of time")
    velocity: signal(u.VELOCITY) | None = Field(None, description="the velocity it drives a mass at: a signal of "
                                                "time")
    position: signal(u.LENGTH) | None = Field(None, description="the position it drives a mass to: a signal of "
                                              "time")
    filter_frequency: u.quantity(u.FREQUENCY, gt=0.0) | None = Field(None, description="f_crit: the reference "
                                                                     "followed through a filter of this "
                                                                     "frequency (none: exactly)")
    name: str = Field("", exclude=True)  # its key in drivetrain.motion_sources (set there, never written)

    @model_validator(mode="after")
    def _one_motion(self):
        given = [key for key in MOTIONS if getattr(self, key) is not None]
        if len(given) != 1:
            key = given[1] if given else "speed"
            raise ScenarioError(f".{key}", "give one motion: speed, angle or acceleration of a shaft, velocity, "
                                "position or acceleration of a mass (a signal of time)")
        if self.filter_frequency is not None and given[0] == "acceleration":
            raise ScenarioError(".filter_frequency", "filters a speed or an angle: an acceleration is followed "
                                "exactly")
        return self

    @property
    def characteristic(self) -> str:
        """Which motion it prescribes: ``speed`` (a mass's velocity too), ``angle`` (a mass's position too) or
        ``acceleration``."""
        given = next(key for key in MOTIONS if getattr(self, key) is not None)
        return {"velocity": "speed", "position": "angle"}.get(given, given)

    def lowered(self, scenario) -> "MotionSourceSpec":
        """With whether it drives a mass written in (``on_line``)."""
        return self.with_resolved(on_line=self.shaft in scenario.drivetrain.masses)

    @property
    def reference(self):
        """The signal it prescribes, whichever its key."""
        return next(getattr(self, key) for key in MOTIONS if getattr(self, key) is not None)


def start_driven_angles(drivetrain) -> None:
    """A shaft driven to an angle starts at its reference's angle at t = 0: its ``angle`` set so (every part that
    reads its shafts' starting angles, a spring's twist, sees it), or refused where it is given otherwise."""
    for name, source in drivetrain.motion_sources.items():
        if source.characteristic != "angle":
            continue
        on_line = source.shaft in drivetrain.masses
        body = (drivetrain.masses if on_line else drivetrain.shafts)[source.shaft]
        key, kind, unit = ("position", "masses", "m") if on_line else ("angle", "shafts", "rad")
        start = source.reference.value_at(0.0)
        if key in body.model_fields_set and abs(getattr(body, key) - start) > 1e-12 * max(1.0, abs(start)):
            raise ScenarioError(f"drivetrain.{kind}.{source.shaft}.{key}", f"is {getattr(body, key):.12g} {unit}, "
                                f"but the motion source {name!r} drives it from {start:.12g} {unit} at t = 0: leave "
                                "it out or give that")
        body._derive(key, start)

"""The schema of a prescribed motion (values in SI): a shaft driven at a speed, an angle or an acceleration given
as a signal of time, whatever torque that takes (Modelica's Rotational.Sources Speed, Position and Accelerate).
"""

from __future__ import annotations

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .signals import signal
from .units import Text

MOTIONS = ("speed", "angle", "acceleration")  # what a source may prescribe, as its keys name it


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
    shaft: Text = Field(description="the shaft it drives (its inertia, and what the shaft's parts take, are the "
                        "source's torque too)")
    speed: signal(u.ANGULAR_SPEED) | None = Field(None, description="the speed it drives the shaft at: a "
                                                          "signal of time")
    angle: signal(u.ANGLE) | None = Field(None, description="the angle it drives the shaft to: a signal "
                                                  "of time")
    acceleration: signal(u.ANGULAR_ACCELERATION) | None = Field(None, description="the acceleration it "
                                                                         "drives the shaft at: a signal of time")
    filter_frequency: u.quantity(u.FREQUENCY, gt=0.0) | None = Field(None, description="f_crit: the reference "
                                                                     "followed through a filter of this "
                                                                     "frequency (none: exactly)")
    name: str = Field("", exclude=True)  # its key in drivetrain.motion_sources (set there, never written)

    @model_validator(mode="after")
    def _one_motion(self):
        given = [key for key in MOTIONS if getattr(self, key) is not None]
        if len(given) != 1:
            key = given[1] if given else "speed"
            raise ScenarioError(f".{key}", "give one motion: speed, angle or acceleration (a signal of time)")
        if self.filter_frequency is not None and given[0] == "acceleration":
            raise ScenarioError(".filter_frequency", "filters a speed or an angle: an acceleration is followed "
                                "exactly")
        return self

    @property
    def characteristic(self) -> str:
        """Which motion it prescribes: ``speed``, ``angle`` or ``acceleration``."""
        return next(key for key in MOTIONS if getattr(self, key) is not None)


def start_driven_angles(drivetrain) -> None:
    """A shaft driven to an angle starts at its reference's angle at t = 0: its ``angle`` set so (every part that
    reads its shafts' starting angles, a spring's twist, sees it), or refused where it is given otherwise."""
    for name, source in drivetrain.motion_sources.items():
        if source.angle is None:
            continue
        shaft = drivetrain.shafts[source.shaft]
        start = source.angle.value_at(0.0)
        if "angle" in shaft.model_fields_set and abs(shaft.angle - start) > 1e-12 * max(1.0, abs(start)):
            raise ScenarioError(f"drivetrain.shafts.{source.shaft}.angle", f"is {shaft.angle:.12g} rad, but the "
                                f"angle source {name!r} drives the shaft from {start:.12g} rad at t = 0: leave it out "
                                "or give that")
        shaft._derive("angle", start)

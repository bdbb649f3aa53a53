"""The schema of a load hanging on a rope (the hoist's ``load:``, a drawn drivetrain's ``drivetrain.load``): its
mass, and a drawn load's shaft, rope radius, elastic rope, the ground under it and its shaft's bearings (values
in SI)."""

from __future__ import annotations

import math
from typing import Literal

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import plausible
from . import units as u
from .schema_base import Section
from .schema_parts import BearingsSpec
from .schema_rope import BufferSpec, GroundSpec, RopeSpec
from .schema_shaft_parts import OnShaft
from .schema_speed_torques import DragSpec
from .units import Text


class LoadSpec(Section):
    """A load hanging on a rope: the hoist's (``load:``, from its drum), and a drawn drivetrain's."""

    mass: u.quantity(u.MASS, plausible=plausible.HOIST_LOAD, ge=0.0) = Field(description="M, lifted against gravity")


class LoadBearingsSpec(BearingsSpec):
    """The bearings of the shaft the load hangs from, which a gear's wheel drives: the tooth forces (from the
    torque the shaft receives, at the wheel's pitch circle), the rope's pull, and the two bearings' reactions."""

    wheel_pitch_diameter: u.quantity(u.LENGTH, plausible=plausible.GEAR_WHEEL_PITCH_DIAMETER, gt=0.0) = Field(
        description="the wheel's, where its teeth are pressed")
    pressure_angle: u.quantity(u.ANGLE, gt=0.0, lt=math.pi / 2) = Field(math.radians(20.0), description="of the "
                                                                        "wheel's teeth")


class LoadOnShaftSpec(OnShaft, LoadSpec):
    """A load hanging from a drawn drivetrain's shaft, its rope wound at a radius: a rigid rope, or an elastic
    one (``rope``); it may start resting on the ground (``ground``).  Or, on a ``level`` path, a load the shaft
    moves through the radius (a wheel's) with no gravity along it; ``drag``: a force against its motion,
    quadratic in its speed."""

    shaft: Text = Field(description="the drum's shaft")
    rope_radius: u.quantity(u.LENGTH, plausible=plausible.DRUM_RADIUS, gt=0.0) = Field(
        description="where the rope winds: half the drum's diameter")
    rope: RopeSpec | None = Field(None, description="an elastic rope (absent: rigid)")
    ground: GroundSpec | None = Field(None, description="the load starts resting on the ground")
    buffer: BufferSpec | None = Field(None, description="a buffer under the load at the end of its travel (with "
                                      "an elastic rope)")
    bearings: LoadBearingsSpec | None = Field(None, description="the shaft's bearing loads in time (a gear "
                                              "stage's output shaft)")
    path: Literal["vertical", "level"] = Field("vertical", description="level: moved along a level path through "
                                               "rope_radius (a wheel's), no gravity along it")
    drag: DragSpec | None = Field(None, description="a force against its motion, quadratic in its speed")

    @property
    def characteristic(self) -> str:
        """Which variant: ``rigid`` (moves with the rope's point on the drum) or ``elastic`` (a body on its rope)."""
        return "level" if self.path == "level" else "rigid" if self.rope is None else "elastic"

    def lowered(self, scenario) -> "LoadOnShaftSpec":
        """With the scene's gravity (m/s^2) and its shaft's speed at the start (rad/s) written in."""
        shaft = scenario.drivetrain.shafts[self.shaft]
        return self.with_resolved(gravity=scenario.gravity, start_speed=shaft.train(scenario)[2])

    @model_validator(mode="after")
    def _a_body_on_its_rope(self):
        if self.rope is not None and self.mass <= 0.0:
            raise ScenarioError(".mass", "must be positive with an elastic rope (rope:): the load is a body of "
                                "its own on it")
        if self.path == "level":
            lifted = next((key for key in ("rope", "ground", "buffer", "bearings") if getattr(self, key) is not None),
                          None)
            if lifted is not None:
                raise ScenarioError(f".{lifted}", "is a hoisted load's: a load on a level path (path: level) "
                                    "moves rigidly with its shaft's radius, with no ground under it")
        buffered(self.buffer, self.rope, self.ground, ".")
        return self



def buffered(buffer, rope, ground, prefix: str) -> None:
    """A buffer is met by a load on an elastic rope (a rigid one would have to push the load into it), and not by
    one that starts on the ground (which holds it up)."""
    if buffer is None:
        return
    if rope is None:
        raise ScenarioError(f"{prefix}buffer", "needs an elastic rope (rope:): the buffer stops the load, the rope "
                            "going slack, which a rigid rope cannot")
    if ground is not None:
        raise ScenarioError(f"{prefix}buffer", "cannot be given with ground: a load resting on the ground at the "
                            "start has no travel below it")

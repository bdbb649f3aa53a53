"""A drawn drivetrain's parts that sit on one shaft: rotors (flywheels), slider-cranks, brakes and ratchets.

Each has the keys of the hoist's section of its kind (:mod:`.schema_parts`) and the shaft it sits on; its
key in the drivetrain names it and its outputs (``<name>_torque``, ...), as the hoist's section's name does
its (``brake_torque``).
"""

from __future__ import annotations

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_parts import BrakeSpec, FlywheelSpec, RatchetSpec, ReciprocatingSpec
from .units import Text


class OnShaft:
    """What a part on a shaft adds to its kind's keys: the shaft, its name (its key, set by the drivetrain), and
    its outputs' names where its drawing names them otherwise than its own name does (the hoist's template)."""

    def output_names(self) -> dict[str, str]:
        """Output name by its pattern (``{name}_torque``) where it is not the pattern filled in."""
        return {}


class RotorSpec(OnShaft, FlywheelSpec):
    """An inertia keyed to a shaft: a flywheel, a drum (given as an inertia or as a rim)."""

    shaft: Text = Field(description="the shaft it sits on")
    name: str = Field("", exclude=True)


class SliderCrankSpec(OnShaft, ReciprocatingSpec):
    """A reciprocating mass on a rod and crank keyed to a shaft."""

    shaft: Text = Field(description="the shaft it sits on")
    name: str = Field("", exclude=True)


class BrakeOnShaftSpec(OnShaft, BrakeSpec):
    """A brake from a shaft to the ground: holding (any torque) or friction (static and kinetic torques),
    released and applied at times, or by a drive's brake sequence (``operated_by``: a speed controller's)."""

    shaft: Text = Field(description="the shaft it sits on")
    release_time: u.quantity(u.TIME, ge=0.0) | None = Field(None, description="the brake frees its shaft at this "
                                                            "time (or operated_by)")
    operated_by: Text | None = Field(None, description="the speed controller whose brake_sequence releases and "
                                     "applies it (a friction brake: static_torque given)")
    name: str = Field("", exclude=True)

    @model_validator(mode="after")
    def _released_by_time_or_by_a_drive(self):
        if (self.release_time is None) == (self.operated_by is None):
            raise ScenarioError(".release_time", "give either release_time (released at a time) or operated_by (a "
                                "speed controller's brake_sequence releases and applies it), one of the two")
        if self.operated_by is not None and (self.static_torque is None or self.apply_time is not None):
            key = ".static_torque" if self.static_torque is None else ".apply_time"
            raise ScenarioError(key, "a brake a drive operates is a friction brake (static_torque) applied by its "
                                "sequence, not at a time")
        return self

    def lowered(self, scenario) -> "BrakeOnShaftSpec":
        """A brake a drive operates with its sequence's opening and closing times written in (s)."""
        if self.operated_by is None:
            return self
        sequence = scenario.drivetrain.speed_controllers[self.operated_by].brake_sequence
        return self.with_resolved(release_delay=sequence.release_delay, close_delay=sequence.close_delay)

    @property
    def characteristic(self) -> str:
        """Which variant: ``holding``, ``friction`` or ``operated`` (a friction brake a drive's sequence works)."""
        return "operated" if self.operated_by is not None else super().characteristic


class RatchetOnShaftSpec(OnShaft, RatchetSpec):
    """A pawl from a shaft to the ground: the shaft may turn forwards, never backwards, until released."""

    shaft: Text = Field(description="the shaft it sits on")
    name: str = Field("", exclude=True)


SHAFT_PARTS = ("rotors", "slider_cranks", "brakes", "ratchets")  # the drivetrain's keys of these kinds


def check_shaft_parts(drivetrain, speeds: dict) -> None:
    """Each part on a shaft names a shaft there is, and is possible at its shaft's speed at the start
    (``speeds``: each shaft's): a holding brake holds a shaft at rest, a pawl a shaft not turning backwards."""
    known = ", ".join(drivetrain.shafts)
    for kind in SHAFT_PARTS:
        for name, part in getattr(drivetrain, kind).items():
            if part.shaft not in drivetrain.shafts:
                raise ScenarioError(f"drivetrain.{kind}.{name}.shaft", f"there is no shaft {part.shaft!r} "
                                    f"(shafts: {known})")
            speed = speeds[part.shaft]
            if kind == "brakes" and part.characteristic == "holding" and speed != 0.0:
                raise ScenarioError(f"drivetrain.{kind}.{name}.static_torque", f"is required: a holding brake "
                                    f"(without static_torque) holds shaft {part.shaft!r} still, which starts at "
                                    f"{speed:g} rad/s")
            if kind == "ratchets" and speed < 0.0:
                raise ScenarioError(f"drivetrain.{kind}.{name}.shaft", f"shaft {part.shaft!r} starts turning "
                                    f"backwards ({speed:g} rad/s): the pawl would stop it dead")

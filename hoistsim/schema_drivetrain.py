"""The schema of a drivetrain drawn as shafts and couplings (``drivetrain:``), values in SI.

Shafts with their inertias and initial speeds, external torques on shafts, and friction clutches between
two shafts or a shaft and ``ground`` (a brake), each torque and force a time signal (:mod:`.signals`).
The names a user gives shafts and clutches name their outputs (``<shaft>_speed``, ``<clutch>_torque``), so
they must be plain words and must not collide.
"""

from __future__ import annotations

import re

from pydantic import model_validator

from . import units as u
from .errors import ScenarioError
from .schema_base import Section
from .signals import signal
from .units import Text

GROUND = "ground"  # the other side of a clutch that is a brake
_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")


class ShaftSpec(Section):
    inertia: u.quantity(u.INERTIA, gt=0.0)
    speed: u.quantity(u.ANGULAR_SPEED) = 0.0  # at t = 0


class TorqueSpec(Section):
    shaft: Text
    torque: signal(u.TORQUE)  # positive in the shaft's positive sense


class FrictionClutchSpec(Section):
    between: tuple[Text, Text]  # [shaft a, shaft b or ground]: its torque passes from a to b
    static_friction: u.quantity(u.DIMENSIONLESS, gt=0.0)
    kinetic_friction: u.quantity(u.DIMENSIONLESS, ge=0.0)
    effective_radius: u.quantity(u.LENGTH, gt=0.0)
    surfaces: u.whole("friction surfaces") = 1
    force: signal(u.FORCE)  # N pressing the faces; at or below zero the clutch is open

    @property
    def torque_per_newton(self) -> float:
        """m: the torque each newton of force gives, per unit friction coefficient."""
        return self.effective_radius * self.surfaces


class DrivetrainSpec(Section):
    shafts: dict[str, ShaftSpec]
    torques: list[TorqueSpec] = []
    clutches: dict[str, FrictionClutchSpec] = {}

    @model_validator(mode="after")
    def _named_and_joined(self):
        if not self.shafts:
            raise ScenarioError("drivetrain.shafts", "give at least one shaft: {name: {inertia, speed}}")
        for kind, names in (("shafts", self.shafts), ("clutches", self.clutches)):
            for name in names:
                if not _NAME.match(name) or name == GROUND:
                    raise ScenarioError(f"drivetrain.{kind}.{name}", "a name is a word of letters, digits and "
                                        f"underscores starting with a letter, and not {GROUND!r}")
        for name in self.clutches:
            if name in self.shafts:
                raise ScenarioError(f"drivetrain.clutches.{name}", f"is also the name of a shaft: names must "
                                    "differ (they name the outputs)")
        known = ", ".join(self.shafts)
        for i, torque in enumerate(self.torques):
            if torque.shaft not in self.shafts:
                raise ScenarioError(f"drivetrain.torques.{i}.shaft", f"there is no shaft {torque.shaft!r} "
                                    f"(shafts: {known})")
        for name, clutch in self.clutches.items():
            a, b = clutch.between
            for side in (a, b):
                if side not in self.shafts and not (side == GROUND and side == b):
                    raise ScenarioError(f"drivetrain.clutches.{name}.between", f"there is no shaft {side!r} "
                                        f"(shafts: {known}; `ground` as the second for a brake)")
            if a == b:
                raise ScenarioError(f"drivetrain.clutches.{name}.between", f"joins shaft {a!r} to itself")
            if clutch.kinetic_friction > clutch.static_friction:
                raise ScenarioError(f"drivetrain.clutches.{name}.kinetic_friction", "must not exceed "
                                    f"static_friction ({clutch.static_friction:g}), got {clutch.kinetic_friction:g}")
        return self


def hoist_only(scenario, command: str) -> None:
    """A command that answers the hoist's questions refuses a drawn drivetrain in one line."""
    if scenario.drivetrain is not None:
        raise ScenarioError("drivetrain", f"{command} answers the hoist's questions (motor, cone clutch, gears, "
                            "drum, load); this scenario draws a drivetrain", source=scenario.source)

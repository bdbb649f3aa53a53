"""Masses on a line drawn beside the shafts (``drivetrain.masses``) and the forces on them (``drivetrain.forces``),
values in SI; and what tells a part on a line from a part between shafts: the bodies it joins, whose units its
values must be written in.
"""

from __future__ import annotations

from dataclasses import dataclass

from pydantic import Field

from ..errors import ScenarioError
from . import unit_words as words
from . import units as u
from .schema_base import Section
from .signals import signal
from .units import Text

GROUND = "ground"


class MassSpec(Section):
    """A mass on a line: a rigid body sliding, with its mass (Modelica's Translational.Components.Mass); its name
    names its outputs, ``<mass>_position`` (m, its centre's) and ``<mass>_velocity`` (m/s)."""

    mass: u.quantity(u.MASS, gt=0.0) = Field(description="m")
    position: u.quantity(u.LENGTH) = Field(0.0, description="s at t = 0 (its centre)")
    velocity: u.quantity(u.VELOCITY) = Field(0.0, description="v at t = 0")
    name: str = Field("", exclude=True)  # its key in drivetrain.masses (set there, never written)


class ForceSpec(Section):
    """An external force on a mass, positive in the line's positive sense, named by its place (force1, force2,
    ...): a signal of time (Modelica's Translational.Sources.Force)."""

    mass: Text = Field(description="the mass it pushes")
    force: signal(u.FORCE) = Field(description="a signal of time")
    name: str = Field("", exclude=True)  # force1, force2, ... in the order of drivetrain.forces (set there)


@dataclass(frozen=True)
class LineKeys:
    """What a kind of part that may join masses says of its keys (its spec's ``line_keys``): the key that names
    the bodies it joins, its keys measured otherwise on a line (a stiffness: N/m there), and its keys of one kind
    of body only."""

    bodies: str  # "between" or "shaft"
    measured: tuple = ()
    line_only: tuple = ()
    shafts_only: tuple = ()


def written_on_line(value: object, dimension: u.Dimension) -> bool | None:
    """Whether a raw value (a quantity, or a table or signal of them) is written in the line's units of a
    dimension that has them (True), in its own (False), or neither can be told (bare numbers: None)."""
    if isinstance(value, dict):
        value = list(value.values())
    if isinstance(value, (list, tuple)):
        said = [written_on_line(item, dimension) for item in value]
        return next((s for s in said if s is not None), None)
    if not isinstance(value, str) or dimension.line is None:
        return None
    try:
        u.to_si(value, dimension.rotational)
        return False
    except u.UnitError:
        pass
    try:
        u.to_si(value, dimension.line)
        return True
    except u.UnitError:
        return None


def check_line_parts(data: dict, kinds: dict) -> None:
    """In a drivetrain's plain data: each part joins bodies of one kind (masses, or shafts), and its values are
    written in that kind's units (a stiffness in N/m between masses, N*m/rad between shafts) with that kind's
    keys.  ``kinds``: each kind of part (its key in the drivetrain) -> its spec, those whose spec says its
    ``line_keys``."""
    masses = data.get("masses") if isinstance(data.get("masses"), dict) else {}
    for kind, spec in kinds.items():
        said: LineKeys = spec.line_keys
        bodies_key = said.bodies
        parts = data.get(kind)
        for name, part in (parts.items() if isinstance(parts, dict) else ()):
            if not isinstance(part, dict):
                continue
            sides = part.get(bodies_key)
            sides = [sides] if isinstance(sides, str) else sides if isinstance(sides, list) else []
            on_line = [side in masses for side in sides if isinstance(side, str) and side != GROUND]
            if on_line and any(on_line) != all(on_line):
                raise ScenarioError(f"drivetrain.{kind}.{name}.{bodies_key}", "joins a mass to a shaft: a part "
                                    "joins masses (on a line) or shafts, and a drum or a rack links the two")
            line = bool(on_line) and all(on_line)
            for key in (said.shafts_only if line else said.line_only):
                if key in part:
                    where = "on a line (of masses)" if line else "of shafts"
                    raise ScenarioError(f"drivetrain.{kind}.{name}.{key}", f"is no key of a part {where}")
            for key in said.measured:
                dimension = u.dimension_of(spec.model_fields[key])
                written = written_on_line(part.get(key), dimension)
                if written is not None and written != line:
                    kind_of = dimension.line if line else dimension.rotational
                    raise ScenarioError(f"drivetrain.{kind}.{name}.{key}", f"is in the units of a part "
                                        f"{'between shafts' if line else 'on a line'}: this one joins "
                                        f"{'masses' if line else 'shafts'}, give {words.a(kind_of.name)} "
                                        f"(like {kind_of.example})")


def start_positions(drivetrain) -> dict:
    """Each body's angle or position at the start (rad or m), the ground's 0."""
    return ({name: shaft.angle for name, shaft in drivetrain.shafts.items()}
            | {name: mass.position for name, mass in drivetrain.masses.items()} | {GROUND: 0.0})

"""Masses on a line drawn beside the shafts (``drivetrain.masses``) and the forces on them (``drivetrain.forces``),
values in SI; and what tells a part on a line from a part between shafts: the bodies it joins, whose units its
values must be written in.
"""

from __future__ import annotations

from dataclasses import dataclass

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import unit_words as words
from . import units as u
from .schema_base import Section
from .schema_gear_groups import gear_groups
from .schema_linkage import start_speeds
from .signals import signal
from .units import Text

GROUND = "ground"


class MassSpec(Section):
    """A mass on a line: a rigid body sliding, with its mass (Modelica's Translational.Components.Mass); its name
    names its outputs, ``<mass>_position`` (m, its centre's) and ``<mass>_velocity`` (m/s)."""

    mass: u.quantity(u.MASS, gt=0.0) = Field(description="m")
    position: u.quantity(u.LENGTH) = Field(0.0, description="s at t = 0 (its centre)")
    velocity: u.quantity(u.VELOCITY) = Field(0.0, description="v at t = 0 (a mass geared to a shaft: the shaft's "
                                             "speed times the radius)")
    name: str = Field("", exclude=True)  # its key in drivetrain.masses (set there, never written)

    def lowered(self, scenario) -> "MassSpec":
        """With its gear train written in: (the first shaft or mass of the body it moves with, its velocity over
        that one's speed, its velocity at the start), as a shaft's (:meth:`ShaftSpec.train`)."""
        groups = gear_groups(scenario.drivetrain)
        root, ratio = groups[self.name]
        return self.with_resolved(train=(root, ratio, start_speeds(scenario.drivetrain, groups)[self.name]))


class ForceSpec(Section):
    """An external force on a mass, positive in the line's positive sense, named by its place (force1, force2,
    ...): a signal of time (Modelica's Translational.Sources.Force)."""

    mass: Text = Field(description="the mass it pushes")
    force: signal(u.FORCE) = Field(description="a signal of time")
    name: str = Field("", exclude=True)  # force1, force2, ... in the order of drivetrain.forces (set there)


class StopsSpec(Section):
    """Hard stops at the ends of a mass's travel (Modelica's MassWithStopAndFriction's smin and smax, given for its
    centre): the mass meets one in an impact, rebounding at ``restitution`` times the speed it arrived at (0: it
    stays, Modelica's), and rests against it while pushed into it, leaving when pulled away; each end writes
    ``<name>_lower_force`` / ``<name>_upper_force`` (its push on the mass, N, in the line's sense) and
    ``_contact``, and the kinetic energy its impacts take (``_impact_loss``, a loss of the ledger)."""

    alternatives = (("lower", "upper", "lower + upper"),)
    mass: Text = Field(description="the mass it stops")
    lower: u.quantity(u.LENGTH) | None = Field(None, description="the lowest position of the mass's centre")
    upper: u.quantity(u.LENGTH) | None = Field(None, description="the highest position of the mass's centre")
    restitution: u.quantity(u.DIMENSIONLESS, ge=0.0, le=1.0) = Field(0.0, description="e: the mass leaves a stop "
                                                                     "at e times the speed it met it at")
    rest_speed: u.quantity(u.VELOCITY, gt=0.0) = Field(1e-3, description="a rebound slower than this rests against "
                                                       "the stop instead (a bounce that would never end)")
    name: str = Field("", exclude=True)  # its key in drivetrain.stops (set there, never written)

    @model_validator(mode="after")
    def _an_end_or_two(self):
        if self.lower is None and self.upper is None:
            raise ScenarioError(".lower", "required: a lower stop, an upper stop or both (the positions of the mass's "
                                "centre where it stops)")
        if self.lower is not None and self.upper is not None and self.lower >= self.upper:
            raise ScenarioError(".upper", f"must be above the lower stop ({self.lower:g} m), got {self.upper:g} m")
        return self

    def check_start(self, starts: dict) -> None:
        """Its mass is a mass of the drivetrain (``starts``: each one's position at the start, the load's too) and
        starts between the stops."""
        where = f"drivetrain.stops.{self.name}"
        if self.mass not in starts:
            raise ScenarioError(f"{where}.mass", f"there is no mass {self.mass!r} (masses: "
                                f"{', '.join(starts) or 'none'})")
        start = starts[self.mass]
        for key, end, beyond in (("lower", self.lower, start < (self.lower or 0.0)),
                                 ("upper", self.upper, start > (self.upper or 0.0))):
            if end is not None and beyond:
                raise ScenarioError(f"{where}.{key}", f"is {'above' if key == 'lower' else 'below'} the start of mass "
                                    f"{self.mass!r} ({start:g} m): a mass starts between its stops")


LOAD = "load"  # a drawn drivetrain's load: the mass on a line parts may join by this name


@dataclass(frozen=True)
class LineKeys:
    """What a kind of part that may join masses says of its keys (its spec's ``line_keys``): the key that names
    the bodies it joins, its keys measured otherwise on a line (a stiffness: N/m there), and its keys of one kind
    of body only."""

    bodies: str | tuple  # "between" or "shaft", or the keys either of which names them
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
    if isinstance(data.get(LOAD), dict):  # the hanging load is a mass on a line too
        masses = {**masses, LOAD: {}}
    for kind, spec in kinds.items():
        said: LineKeys = spec.line_keys
        parts = data.get(kind)
        for name, part in (parts.items() if isinstance(parts, dict) else ()):
            if not isinstance(part, dict):
                continue
            keys = (said.bodies,) if isinstance(said.bodies, str) else said.bodies
            bodies_key = next((key for key in keys if key in part), keys[0])
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


def line_starts(drivetrain) -> dict:
    """Each mass on the line's position at the start (m): the drawn masses', and the load's (its height, 0 where it
    starts) where the drivetrain has one."""
    load = {} if drivetrain.load is None else {LOAD: 0.0}
    return {name: mass.position for name, mass in drivetrain.masses.items()} | load


def start_positions(drivetrain) -> dict:
    """Each body's angle or position at the start (rad or m), the ground's 0."""
    return {name: shaft.angle for name, shaft in drivetrain.shafts.items()} | line_starts(drivetrain) | {GROUND: 0.0}

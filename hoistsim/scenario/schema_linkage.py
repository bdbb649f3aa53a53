"""A drawn drivetrain's linkages of three shafts: planetary sets (``drivetrain.planetaries``) and gear stages on
a housing that turns (``drivetrain.gears.<name>.housing``), values in SI.

Each holds a linear relation among its shafts' speeds, sum w_i speed_i = 0, that gearing shafts into one body
(one speed ratio a shaft) cannot: the shafts stay bodies (or shafts geared to them) tied by the relation.  Their
speeds at the start must keep it: a left-out speed is derived from the others, given ones that disagree are
refused.
"""

from __future__ import annotations

import re

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import units as u
from .schema_base import Section
from .schema_gear_groups import given_speed
from .units import Text

_NAME = re.compile(r"^[A-Za-z][A-Za-z0-9_]*$")  # as every part's name (schema_drivetrain)


class PlanetarySpec(Section):
    """A planetary set: sun, carrier and ring, (1 + r) w_carrier = w_sun + r w_ring (Willis), r the ring's teeth
    over the sun's (Modelica's IdealPlanetary)."""

    alternatives = (("ratio", "teeth"),)
    sun: Text = Field(description="the sun's shaft")
    carrier: Text = Field(description="the carrier's shaft")
    ring: Text = Field(description="the ring's shaft")
    ratio: u.quantity(u.DIMENSIONLESS) | None = Field(None, description="r = z_ring / z_sun, above 1")
    teeth: tuple[u.whole("teeth"), u.whole("teeth")] | None = Field(None, description="[z_sun, z_ring]: ratio "
                                                                    "z_ring / z_sun")
    name: str = Field("", exclude=True)  # its key in drivetrain.planetaries (set there, never written)

    @model_validator(mode="after")
    def _one_ratio_above_one(self):
        if (self.ratio is None) == (self.teeth is None):
            raise ScenarioError(".ratio", "give either ratio (the ring's teeth over the sun's) or teeth [sun, ring], "
                                "one of them")
        if self.teeth is not None:
            self._derive("ratio", self.teeth[1] / self.teeth[0])
        if not self.ratio > 1.0:
            where = ".ratio" if self.teeth is None else ".teeth"
            raise ScenarioError(where, f"the ring's teeth over the sun's must be above 1 (the ring is outside the "
                                f"sun and its planets), got {self.ratio:.6g}")
        return self

    def members(self) -> tuple:
        """(key, shaft, weight) of its shafts: sun 1, carrier -(1 + r), ring r."""
        return (("sun", self.sun, 1.0), ("carrier", self.carrier, -(1.0 + self.ratio)), ("ring", self.ring, self.ratio))


def housed_members(stage) -> tuple:
    """(key, shaft, weight) of a gear stage's shafts on its housing: input 1, output -r, housing r - 1."""
    (a, b), r = stage.between, stage.ratio
    return (("between", a, 1.0), ("between", b, -r), ("housing", stage.housing, r - 1.0))


def linkages(drivetrain) -> list:
    """(its key, its relation in words, its (key, shaft, weight) members) of each linkage of the drivetrain."""
    out = [(f"drivetrain.planetaries.{name}", "planetary set, (1 + ratio) w_carrier = w_sun + ratio w_ring",
            spec.members()) for name, spec in drivetrain.planetaries.items()]
    out += [(f"drivetrain.gears.{name}", "gear stage on its housing, w_in - w_housing = ratio (w_out - w_housing)",
             housed_members(stage)) for name, stage in drivetrain.gears.items() if stage.housing is not None]
    return out


def check_linkages(drivetrain, seen: dict) -> None:
    """Each planetary set is named as a part (``seen``: the names taken, updated) and ties three distinct shafts
    there are; each housing is a shaft there is, not one of its stage's own, under an ideal stage."""
    known = ", ".join(drivetrain.shafts)
    for name, spec in drivetrain.planetaries.items():
        key = f"drivetrain.planetaries.{name}"
        if not _NAME.match(name) or name == "ground" or name in seen:
            raise ScenarioError(key, "a name is a word of letters, digits and underscores starting with a letter, "
                                "not 'ground' and not the name of another part (they name the outputs)")
        seen[name] = "planetaries"
        for word, shaft, _ in spec.members():
            if shaft not in drivetrain.shafts:
                raise ScenarioError(f"{key}.{word}", f"there is no shaft {shaft!r} (shafts: {known})")
        shafts = [shaft for _, shaft, _ in spec.members()]
        if len(set(shafts)) < 3:
            raise ScenarioError(key, f"ties shafts {', '.join(shafts)}: a planetary set turns three distinct shafts "
                                "(sun, carrier, ring)")
    for name, stage in drivetrain.gears.items():
        if stage.housing is None:
            continue
        key = f"drivetrain.gears.{name}"
        if stage.housing in stage.between:
            raise ScenarioError(f"{key}.housing", f"is shaft {stage.housing!r}, one of the stage's own (between): "
                                "the housing is a third shaft")
        if stage.housing not in drivetrain.shafts:
            raise ScenarioError(f"{key}.housing", f"there is no shaft {stage.housing!r} (shafts: {known})")
        if stage.lossy:
            raise ScenarioError(f"{key}.{stage.loss_key}", "a stage on a housing is ideal here: give it no "
                                f"{stage.loss_key}")


def start_speeds(drivetrain, groups: dict) -> dict:
    """Each shaft's speed at the start (rad/s; a mass's velocity, m/s): its gear train's (``groups``: shaft -> (root,
    speed over the root's)), the root's as given (or, left out, the first speed given in its train); a root left
    out that a linkage ties to shafts of known speeds takes the speed the relation gives it (in turn, as far as
    the linkages reach), any other left out is at rest.
    Given speeds that break a linkage's relation are refused, naming the last given shaft (or the linkage)."""
    known = {root: speed for root, _ in groups.values() if (speed := given_speed(drivetrain, root)) is not None}
    for name, (root, ratio) in groups.items():  # a train whose first body is left out: a speed given in it
        speed = given_speed(drivetrain, name)
        if root not in known and speed is not None:
            known[root] = speed / ratio
    given = set(known)
    rows = []  # (linkage key, relation, members, root -> weight on the root's speed)
    for key, relation, members in linkages(drivetrain):
        row: dict = {}
        for _, shaft, weight in members:
            root, ratio = groups[shaft]
            row[root] = row.get(root, 0.0) + weight * ratio
        rows.append((key, relation, members, row))
    derived = True
    while derived:
        derived = False
        for _, _, _, row in rows:
            unknown = [root for root, w in row.items() if root not in known and w != 0.0]
            if len(unknown) == 1:
                (root,) = unknown
                known[root] = -sum(w * known[r] for r, w in row.items() if r != root and w != 0.0) / row[root]
                derived = True
    for key, relation, members, row in rows:
        terms = [w * known.get(root, 0.0) for root, w in row.items()]
        if abs(sum(terms)) <= 1e-9 * sum(abs(t) for t in terms) + 1e-12:
            continue
        named = [(word, shaft) for word, shaft, _ in members if groups[shaft][0] in given]
        word, shaft = named[-1]
        root, ratio = groups[shaft]
        if len({groups[s][0] for _, s, _ in members} - given) > 0 or row[root] == 0.0:
            raise ScenarioError(key, f"ties shafts whose speeds at the start break its relation ({relation}): give "
                                "the speeds of all its shafts but one, which is derived")
        others = ", ".join(s for _, s, _ in members if groups[s][0] != root)
        expected = -sum(w * known.get(r, 0.0) for r, w in row.items() if r != root) / row[root] * ratio
        raise ScenarioError(f"drivetrain.shafts.{shaft}.speed", f"is tied to {others} by {key} ({relation}): its "
                            f"speed must be {expected:.12g} rad/s (or left out), got {ratio * known[root]:.12g} rad/s")
    return {shaft: known.get(root, 0.0) * ratio for shaft, (root, ratio) in groups.items()}


"""A drawn drivetrain's bearing friction (``drivetrain.bearing_frictions``): a friction torque of a shaft against
the ground, or between two shafts, that depends on the speed of slip; on a line, a friction force of a mass against
the ground or between masses (values in SI)."""

from __future__ import annotations

from typing import ClassVar

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import tables
from . import units as u
from .dimensions import Dimension
from .schema_base import Section
from .schema_masses import LineKeys
from .units import Text

# the Stribeck law's keys, between shafts or on a line (N, N*s/m, s/m there)
FRICTION = u.TORQUE.on_line(u.FORCE)
VISCOUS = u.TORSIONAL_DAMPING.on_line(u.DAMPING)
DECAY = Dimension("decay per speed", "s/rad", "'2 s/rad'", radians=-1).on_line(
    Dimension("decay per velocity", "s/m", "'2 s/m'"))
STRIBECK_KEYS = ("stribeck", "decay", "viscous")


class BearingFrictionSpec(Section):
    """Modelica's BearingFriction: it sticks until the torque across it exceeds ``peak`` times its friction
    torque at rest, and slips at its friction torque, a constant or a table of the slip speed's size
    (Modelica's tau_pos), the same either way.  A constant may grow a Stribeck curve (Modelica's
    MassWithStopAndFriction): torque + stribeck exp(-decay w) + viscous w at a slip of size w.  On a mass (``between``
    a mass and ``ground``, or two masses) it is Modelica's SupportFriction: a ``force`` (N, a table's slip in
    m/s) where a shaft's has a torque, its Stribeck keys in N, s/m and N*s/m."""

    alternatives = (("shaft", "between"), ("torque", "force"))
    line_keys: ClassVar[LineKeys] = LineKeys(("between", "shaft"), measured=STRIBECK_KEYS, line_only=("force",),
                                             shafts_only=("torque", "shaft"))
    shaft: Text | None = Field(None, description="on a shaft: friction against the ground (its housing)")
    between: tuple[Text, Text] | None = Field(None, description="[shaft a, shaft b]: between two shafts (b may be "
                                              "ground), or two masses (a mass and ground)")
    torque: tables.SlipTorque | None = Field(None, description="its friction torque: a constant, or a table of the "
                                             "slip speed's size, flat beyond the rows")
    force: tables.SlipForce | None = Field(None, description="on a line: its friction force, a constant or a table "
                                           "of the slip velocity's size, flat beyond the rows")
    stribeck: u.quantity(FRICTION, ge=0.0) = Field(0.0, description="with a constant torque (force): the Stribeck "
                                                   "effect, the friction at rest above it, decaying with the slip "
                                                   "(Modelica's F_Stribeck)")
    decay: u.quantity(DECAY, ge=0.0) = Field(0.0, description="the Stribeck effect's decay: exp(-decay w), w the "
                                             "slip's size (Modelica's fexp)")
    viscous: u.quantity(VISCOUS, ge=0.0) = Field(0.0, description="a friction growing with the slip's size w: "
                                                 "viscous w (Modelica's F_prop)")
    peak: u.quantity(u.DIMENSIONLESS, ge=1.0) = Field(1.0, description="the most it holds stuck: peak times its "
                                                      "friction at rest")
    name: str = Field("", exclude=True)  # its key in drivetrain.bearing_frictions (set there, never written)

    @model_validator(mode="after")
    def _on_a_shaft_or_between_two(self):
        if (self.shaft is None) == (self.between is None):
            raise ScenarioError(".shaft", "give either shaft (friction against the ground) or between [a, b] "
                                "(between two shafts), one of them")
        if (self.torque is None) == (self.force is None):
            raise ScenarioError(".torque", "give either torque (between shafts) or force (on a line, between "
                                "masses), one of them")
        if self.slip_table is not None:
            given = next((key for key in STRIBECK_KEYS if getattr(self, key) != 0.0), None)
            if given is not None:
                raise ScenarioError(f".{given}", "is a Stribeck curve's, grown on a constant friction: a table of "
                                    "the slip speed already gives the friction at every slip")
        return self

    @property
    def sides(self) -> tuple[str, str]:
        """(shaft a, shaft b or ground): its torque passes from a to b."""
        return (self.shaft, "ground") if self.between is None else self.between

    @property
    def friction(self):
        """Its friction torque (or a line's force): a constant, or a table's rows."""
        return self.torque if self.force is None else self.force

    @property
    def slip_table(self) -> tuple | None:
        """The friction's rows [slip speed (rad/s or m/s), torque (N*m or N)], or None where it is a constant."""
        return self.friction if isinstance(self.friction, tuple) else None

    @property
    def torque_at_rest(self) -> float:
        """Its friction at zero slip (N*m or N): the constant with its Stribeck effect, or the table's first row."""
        table = self.slip_table
        return self.friction + self.stribeck if table is None else table[0][1]

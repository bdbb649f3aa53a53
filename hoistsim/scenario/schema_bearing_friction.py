"""A drawn drivetrain's bearing friction (``drivetrain.bearing_frictions``): a friction torque of a shaft against
the ground, or between two shafts, that depends on the speed of slip (values in SI)."""

from __future__ import annotations

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import tables
from . import units as u
from .schema_base import Section
from .units import Text


class BearingFrictionSpec(Section):
    """Modelica's BearingFriction: it sticks until the torque across it exceeds ``peak`` times its friction
    torque at rest, and slips at its friction torque, a constant or a table of the slip speed's size
    (Modelica's tau_pos), the same either way."""

    alternatives = (("shaft", "between"),)
    shaft: Text | None = Field(None, description="on a shaft: friction against the ground (its housing)")
    between: tuple[Text, Text] | None = Field(None, description="[shaft a, shaft b]: between two shafts (b may be "
                                              "ground)")
    torque: tables.SlipTorque = Field(description="its friction torque: a constant, or a table of the slip "
                                      "speed's size, flat beyond the rows")
    peak: u.quantity(u.DIMENSIONLESS, ge=1.0) = Field(1.0, description="the most it holds stuck: peak times its "
                                                      "torque at rest")
    name: str = Field("", exclude=True)  # its key in drivetrain.bearing_frictions (set there, never written)

    @model_validator(mode="after")
    def _on_a_shaft_or_between_two(self):
        if (self.shaft is None) == (self.between is None):
            raise ScenarioError(".shaft", "give either shaft (friction against the ground) or between [a, b] "
                                "(between two shafts), one of them")
        return self

    @property
    def sides(self) -> tuple[str, str]:
        """(shaft a, shaft b or ground): its torque passes from a to b."""
        return (self.shaft, "ground") if self.between is None else self.between

    @property
    def slip_table(self) -> tuple | None:
        """The friction torque's rows [slip speed (rad/s), torque (N*m)], or None where it is a constant."""
        return self.torque if isinstance(self.torque, tuple) else None

    @property
    def torque_at_rest(self) -> float:
        """Its friction torque at zero slip (N*m): the constant, or the table's first row."""
        table = self.slip_table
        return self.torque if table is None else table[0][1]

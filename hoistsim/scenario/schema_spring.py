"""A drawn drivetrain's torsional springs and dampers (``drivetrain.springs``): between two shafts, or a shaft
and ``ground`` (values in SI)."""

from __future__ import annotations

import math
from typing import ClassVar

from pydantic import Field, model_validator

from ..errors import ScenarioError
from . import plausible
from . import units as u
from .schema_base import Section
from .schema_masses import LineKeys, line_starts, start_positions
from .units import Text

# between shafts, or between masses (on a line: N/m and N*s/m)
STIFFNESS = u.TORSIONAL_STIFFNESS.on_line(u.STIFFNESS)
DAMPING = u.TORSIONAL_DAMPING.on_line(u.DAMPING)


class SpringSpec(Section):
    """A torsional spring c and a damper d in parallel, from shaft a to shaft b (or ``ground``): it passes
    tau = c (phi_rel - unstretched_angle) + d w_rel, phi_rel and w_rel b's angle and speed less a's (Modelica's
    SpringDamper; a Spring without damping, a Damper without stiffness).  Between two masses (or a mass and
    ``ground``) it is the line's: f = c (s_rel - unstretched_length) + d v_rel, c in N/m and d in N*s/m, s_rel the
    distance of their centres."""

    alternatives = (("stiffness", "shear_modulus + diameter + length", "damping alone (a damper)"),)
    line_keys: ClassVar[LineKeys] = LineKeys("between", measured=("stiffness", "damping"),
                                             line_only=("unstretched_length",),
                                             shafts_only=("unstretched_angle", "shear_modulus", "diameter",
                                                          "inner_diameter", "length", "backlash"))
    between: tuple[Text, Text] = Field(description="[shaft a, shaft b]: either may be ground (the housing), not "
                                       "both")
    stiffness: u.quantity(STIFFNESS, ge=0.0) | None = Field(None, description="c (absent: a damper)")
    # or a round shaft's: c = G pi (D^4 - D_i^4) / (32 L)
    shear_modulus: u.quantity(u.PRESSURE, gt=0.0) | None = Field(None, description="G of a round shaft (steel: "
                                                                 "79-81 GPa): c = G pi (D^4 - D_i^4) / (32 L)")
    diameter: u.quantity(u.LENGTH, plausible=plausible.SHAFT_DIAMETER, gt=0.0) | None = Field(
        None, description="D, the round shaft's")
    inner_diameter: u.quantity(u.LENGTH, plausible=plausible.SHAFT_DIAMETER, ge=0.0) = Field(
        0.0, description="D_i, a hollow shaft's bore")
    length: u.quantity(u.LENGTH, plausible=plausible.SHAFT_LENGTH, gt=0.0) | None = Field(
        None, description="L, between the parts it joins")
    damping: u.quantity(DAMPING, ge=0.0) = Field(0.0, description="d")
    unstretched_angle: u.quantity(u.ANGLE) = Field(0.0, description="phi_rel0: the twist at which it passes no "
                                                   "torque")
    unstretched_length: u.quantity(u.LENGTH) | None = Field(None, description="s_rel0, between masses: the "
                                                            "distance of their centres at which it passes no force")
    backlash: u.quantity(u.ANGLE, ge=0.0) | None = Field(None, description="b: the total play (Modelica's "
                                                         "ElastoBacklash)")
    gap: bool = Field(False, description="true: it only pushes, touching while compressed below its unstretched "
                      "length (or angle), its damping limited to its spring's force (Modelica's ElastoGap: a "
                      "buffer, a stop with give)")
    name: str = Field("", exclude=True)  # its key in drivetrain.springs (set there, never written)

    def lowered(self, scenario) -> "SpringSpec":
        """With its twist at the start written in: b's angle less a's (a shaft's ``angle``, the ground's 0)."""
        start = start_positions(scenario.drivetrain)
        return self.with_resolved(initial_twist=start[self.between[1]] - start[self.between[0]],
                                  on_line=not line_starts(scenario.drivetrain).keys().isdisjoint(self.between))

    @model_validator(mode="after")
    def _a_spring_or_a_damper(self):
        if self.unstretched_length is not None:  # between masses: the same law's rest point, in metres
            self._derive("unstretched_angle", self.unstretched_length)
        keys = (self.stiffness, self.shear_modulus, self.diameter, self.length)
        damper = all(value is None for value in keys) and self.damping > 0.0  # a damping alone
        shaft = not damper and self._one_value_or_group(
            "", "stiffness", ("shear_modulus", "diameter", "length"),
            both="stiffness or a shaft's shear_modulus, diameter and length",
            required="a stiffness, or a shaft's shear_modulus, diameter and length (or a damping alone: a damper)")
        if shaft and self.inner_diameter >= self.diameter:
            raise ScenarioError(".inner_diameter", f"must be less than the diameter ({self.diameter:g} m), got "
                                f"{self.inner_diameter:g} m")
        if self.backlash is not None and self.spring_rate == 0.0:
            raise ScenarioError(".stiffness", "is required with backlash: the sides meet through the spring (a "
                                "contact without stiffness would pass no torque)")
        if self.gap and self.backlash is not None:
            raise ScenarioError(".gap", "give either backlash (a play both ways) or gap (a contact one way), not both")
        if self.gap and self.spring_rate == 0.0:
            raise ScenarioError(".stiffness", "is required with gap: the sides push through the spring (its "
                                "damping is limited to the spring's force)")
        if self.spring_rate == 0.0 and self.damping == 0.0:
            raise ScenarioError(".stiffness", "give a stiffness, a damping or both (a spring of neither passes "
                                "no torque)")
        return self

    @property
    def characteristic(self) -> str:
        """Which variant: ``spring`` (a spring-damper), ``backlash`` (one with play) or ``gap`` (one that only
        pushes)."""
        return "gap" if self.gap else "spring" if self.backlash is None else "backlash"

    @property
    def spring_rate(self) -> float:
        """c (N*m/rad): as given, or the round shaft's G pi (D^4 - D_i^4) / (32 L); 0 for a damper."""
        if self.stiffness is not None:
            return self.stiffness
        if self.diameter is None:
            return 0.0
        return self.shear_modulus * math.pi * (self.diameter**4 - self.inner_diameter**4) / (32.0 * self.length)

"""An ideal gear stage whose housing is a shaft of the machine (Modelica's IdealGear with its support used)."""

from __future__ import annotations

from ..._pytree import static
from ._linkage import AbstractLinkage


class HousedGear(AbstractLinkage):
    """w_in - w_h = r (w_out - w_h), r the input's speed over the output's, both against the housing: the
    input, the output and the housing weigh 1, -r and r - 1.  The housing bears the difference of the
    shafts' torques: the reaction (r - 1) T of an input torque T.  Outputs ``<name>_input_torque``,
    ``<name>_output_torque``, ``<name>_housing_torque``: the torque each shaft drives the stage with
    (Modelica's flange_a.tau, flange_b.tau, support.tau)."""

    ratio: object  # r
    driving: str = static("")  # the input shaft
    driven: str = static("")  # the output shaft
    housing: str = static("")
    section: str = static("")  # the stage's name

    @classmethod
    def from_spec(cls, spec) -> "HousedGear":
        return cls(ratio=spec.ratio, driving=spec.between[0], driven=spec.between[1], housing=spec.housing,
                   section=spec.name)

    def members(self) -> tuple:
        return (("input", self.driving, 1.0), ("output", self.driven, -self.ratio),
                ("housing", self.housing, self.ratio - 1.0))

"""What a torque of a shaft's speed given by a law shares (Modelica's Linear- and QuadraticSpeedDependentTorque):
its nominal torque and speed, whether its sign follows the speed's, and its column."""

from __future__ import annotations

from typing import ClassVar

from ..._pytree import static
from ._shaft_work import AbstractShaftWork


class AbstractSpeedLawTorque(AbstractShaftWork):
    """tau_n f(w / w_n) on its shaft, its spec the torque entry's ``law`` key (``quadratic``, ``linear``)."""

    law: ClassVar[str] = ""  # the torque entry's key that gives it
    nominal_torque: object  # tau_n, N*m
    nominal_speed: object  # w_n, rad/s
    shaft: str = static("")
    section: str = static("")  # torque1, torque2, ... in the order of drivetrain.torques
    reverses: bool = static(True)  # its sign follows the speed's (Modelica's TorqueDirection = false)

    @classmethod
    def from_spec(cls, spec) -> "AbstractSpeedLawTorque":
        law = getattr(spec, cls.law)
        return cls(nominal_torque=law.nominal_torque, nominal_speed=law.nominal_speed, shaft=spec.shaft,
                   section=spec.name, reverses=law.direction == "reverses")

    @property
    def columns(self) -> dict:
        return {self.section: ("N*m", f"torque on shaft {self.shaft}, {self.law} in its speed")}

    def outputs(self, x) -> dict:
        return {self.section: self.torque(x)}

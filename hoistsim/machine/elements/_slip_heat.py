"""What a friction coupling's heat is: the power of its slip, summed in a state, a loss of the ledger."""

from __future__ import annotations

from typing import ClassVar

from ..core.element import AbstractCoupling


def slip_power(x, section: str):
    """The heat of slip of a coupling (W): the torque it passes times its sides' relative speed."""
    return x.coupling_torque(section) * x.relative_speed(section)


class AbstractSlipHeat(AbstractCoupling):
    """A coupling whose heat of slip (the torque it passes times its sides' relative speed) is the state
    ``heat_state`` (J so far), declared a loss of the energy ledger."""

    heat_state: ClassVar[str]

    @property
    def ledger_kinds(self) -> dict:
        return {self.heat_state: "loss"}

    def slip_power(self, x):
        return slip_power(x, self.section)

    def states(self) -> dict:
        return {self.heat_state: 0.0}

    def rates(self, x) -> dict:
        return {self.heat_state: self.slip_power(x)}

    def ledger(self, x) -> dict:
        return {self.heat_state: x.state(self.heat_state)}

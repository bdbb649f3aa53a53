"""What a torque on a drawn drivetrain's shaft shares, a signal's or a motor's: its work, a term of the ledger."""

from __future__ import annotations

import abc

from ..core.element import AbstractElement


class AbstractShaftWork(AbstractElement):
    """A torque ``torque(x)`` on the shaft ``self.shaft``, whose work on it is the state
    ``<section>_work`` and a work term of the energy ledger (subclasses declare ``shaft`` and ``section``)."""

    @abc.abstractmethod
    def torque(self, x):
        """The torque on the shaft (N*m), positive in its positive sense."""

    @property
    def work_state(self) -> str:
        return f"{self.section}_work"

    @property
    def ledger_kinds(self) -> dict:
        return {self.work_state: "work"}

    def torques(self, x) -> tuple:
        return ((self.shaft, self.torque(x)),)

    def states(self) -> dict:
        return {self.work_state: 0.0}

    def rates(self, x) -> dict:
        return {self.work_state: self.torque(x) * x.speed(self.shaft)}

    def ledger(self, x) -> dict:
        return {self.work_state: x.state(self.work_state)}

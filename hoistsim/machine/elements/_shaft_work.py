"""What a torque on a drawn drivetrain's shaft shares, a signal's, a motor's or a drive's: its work, a term of the
ledger."""

from __future__ import annotations

import abc

from ..core.element import AbstractElement


class AbstractWorkOnShaft(AbstractElement):
    """A torque ``torque(x)`` on the shaft ``self.shaft`` whose work on it is the state ``<section>_work`` and a
    work term of the energy ledger (subclasses declare ``shaft`` and ``section``); how the torque reaches the
    shaft is the subclass's (applied to it, or passed by a coupling)."""

    @abc.abstractmethod
    def torque(self, x):
        """The torque on the shaft (N*m), positive in its positive sense."""

    @property
    def work_state(self) -> str:
        return f"{self.section}_work"

    @property
    def ledger_kinds(self) -> dict:
        return {self.work_state: "work"}

    def states(self) -> dict:
        return {self.work_state: 0.0}

    def rates(self, x) -> dict:
        return {self.work_state: self.torque(x) * x.speed(self.shaft)}

    def ledger(self, x) -> dict:
        return {self.work_state: x.state(self.work_state)}


class AbstractShaftWork(AbstractWorkOnShaft):
    """A torque applied to its shaft: an external torque of the bodies' equations."""

    def torques(self, x) -> tuple:
        return ((self.shaft, self.torque(x)),)

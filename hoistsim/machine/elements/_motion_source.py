"""What a prescribed motion shares, a speed's, an angle's or an acceleration's: a drive holding a shaft to it."""

from __future__ import annotations

import abc
from typing import ClassVar

import jax.numpy as jnp

from ..core.element import AbstractCoupling
from ._shaft_work import AbstractWorkOnShaft


class AbstractMotionSource(AbstractWorkOnShaft, AbstractCoupling):
    """A coupling of the shaft ``self.shaft`` to the ground that is always stuck and holds the shaft at the motion
    ``motion(x)`` gives (a drive: the core solves for the torque that takes, and keeps the speed it holds where
    couplings lock or a boundary is passed).  The torque it applies to the shaft is its output
    ``<section>_torque``; its work on the shaft (that torque times the shaft's speed, and its impulses' work where
    the speed it holds jumps) is the state ``<section>_work`` and a work term of the energy ledger.  Subclasses
    declare ``shaft`` and ``section``."""

    can_slip: ClassVar[bool] = False
    reports_switches: ClassVar[bool] = False
    drives: ClassVar[bool] = True

    @abc.abstractmethod
    def motion(self, x) -> tuple:
        """(the shaft's speed it holds, or None: the speed it has; its acceleration), rad/s and rad/s^2."""

    @property
    def columns(self) -> dict:
        return {f"{self.section}_torque": ("N*m", f"torque the motion source {self.section} applies to shaft "
                                                  f"{self.shaft}, positive in its positive sense")}

    def joins(self) -> tuple:
        return (self.shaft, None)

    def capacity(self, x):
        return jnp.inf

    def sliding_torque(self, x):
        return 0.0

    def torque(self, x):
        """What it applies to the shaft (N*m): the opposite of what the shaft passes into it."""
        return -x.coupling_torque(self.section)

    def outputs(self, x) -> dict:
        return {f"{self.section}_torque": self.torque(x)}

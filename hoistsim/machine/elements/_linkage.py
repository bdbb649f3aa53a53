"""What a planetary set and a gear stage on a moving housing share: a rigid linear relation among three shafts."""

from __future__ import annotations

import abc
from typing import ClassVar

import jax.numpy as jnp

from ..core.element import AbstractCoupling


class AbstractLinkage(AbstractCoupling):
    """Three shafts whose speeds keep sum w_i speed_i = 0 (the weights sum to zero: no torque reaches the
    ground), ideal: no inertia, no loss.

    A coupling that is always stuck and holds any torque: a row of the bodies' constrained solve, which
    the machine's shafts geared into one body cannot hold (one speed ratio a shaft).  It never slips and
    never opens, so it has no guard and no switch; where the machine's couplings lock, it keeps its
    relation through the momentum-keeping reset.  The solve's torque T is taken w_i T from each shaft:
    w_i T is the torque shaft i drives the set with (Modelica's flange tau), the set turning shaft i with
    -w_i T, and the power sum_i w_i T speed_i is zero.
    """

    can_slip: ClassVar[bool] = False
    reports_switches: ClassVar[bool] = False
    observes_slip_peak: ClassVar[bool] = False

    @abc.abstractmethod
    def members(self) -> tuple:
        """((its word for the shaft, the shaft, its weight), ...), three of them."""

    def joins(self) -> tuple:
        return tuple(shaft for _, shaft, _ in self.members())

    def weights(self) -> tuple:
        return tuple((shaft, weight) for _, shaft, weight in self.members())

    def capacity(self, x):
        return jnp.inf

    def sliding_torque(self, x):
        return 0.0

    def torques_on_members(self, x) -> dict:
        """Its word for each shaft -> the torque that shaft drives it with (N*m, w_i T)."""
        torque = x.coupling_torque(self.section)
        return {word: weight * torque for word, _, weight in self.members()}

    @property
    def columns(self) -> dict:
        return {f"{self.section}_{word}_torque": ("N*m", f"torque shaft {shaft} (the {word}) drives {self.section} "
                                                         "with; it turns the shaft with minus it")
                for word, shaft, _ in self.members()}

    def outputs(self, x) -> dict:
        return {f"{self.section}_{word}_torque": value for word, value in self.torques_on_members(x).items()}

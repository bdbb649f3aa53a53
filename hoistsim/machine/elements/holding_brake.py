"""A holding brake: keeps a shaft (the hoist's drum) still until it is released."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ._shaft_hold import AbstractShaftHold


class HoldingBrake(AbstractShaftHold):
    """A coupling of a shaft to the ground, stuck until ``release_time``, open after.

    It holds any torque (no capacity limit) and never slips.  The release is a
    scheduled discontinuity: a segment boundary of the integration and the
    event ``<name>_release`` (the hoist's ``brake_release``).
    """

    can_slip: ClassVar[bool] = False
    reports_switches: ClassVar[bool] = False

    @classmethod
    def from_spec(cls, spec) -> "HoldingBrake":
        return cls(release_time=spec.release_time, shaft=spec.shaft, section=spec.name)

    def capacity(self, x):
        return jnp.inf

    def sliding_torque(self, x):
        return 0.0

"""What a pawl and the ground share: a hold one way only."""

from __future__ import annotations

import jax.numpy as jnp


class OneWayHold:
    """A coupling that holds any torque pushing its side a backwards (a load that would lower the drum,
    a load pressing on the ground) and none pushing it forwards: a drive that lifts frees it, and it
    "slips" forwards passing nothing."""

    def capacity(self, x):
        return jnp.inf

    def capacity_toward(self, x, sign):
        return jnp.where(sign > 0, 0.0, jnp.inf)

    def sliding_torque(self, x):
        return 0.0

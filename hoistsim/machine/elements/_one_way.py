"""What a pawl and the ground share: a hold one way only."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp


class OneWayHold:
    """A coupling that holds any torque pushing its side a backwards (a load that would lower the drum,
    a load pressing on the ground) and none pushing it forwards: a drive that lifts frees it, and it
    "slips" forwards passing nothing.

    Its capacity is infinite one way and nothing the other, so its margin to breakaway is finite only one way:
    that way's margin has a valley guard of its own (``margin_each_way``), so that a machine held at rest, with
    nothing to limit its steps, cannot hide within one step a torque that turns to pull the hold off and back
    (a mass resting on its stop, the push of a spring and a harmonic force turning round)."""

    margin_each_way: ClassVar[bool] = True

    def capacity(self, x):
        return jnp.inf

    def capacity_toward(self, x, sign):
        return jnp.where(sign > 0, 0.0, jnp.inf)

    def sliding_torque(self, x):
        return 0.0

"""A one-way clutch: a freewheel and a friction clutch side by side between two shafts."""

from __future__ import annotations

import jax.numpy as jnp

from .friction_clutch import FrictionClutch


class OneWayClutch(FrictionClutch):
    """Modelica's OneWayClutch between shafts a and b: shaft b may overrun a (turn faster forwards), a never
    overruns b.  Stuck, it holds any torque that would drive a faster than b (the freewheel locks), and a
    torque the other way up to the friction clutch's static capacity; b overrunning, the clutch slips at its
    sliding torque (nothing while its force is at or below zero: the freewheel alone).

    A friction clutch in all else (its keys, outputs, heat, a kinetic friction that may be a table of the slip
    speed), except that it is never open: released, its freewheel still holds one way.
    """

    def capacity_toward(self, x, sign):
        # sign > 0: a torque driving shaft a forwards past b, which the freewheel holds whatever it is
        return jnp.where(sign > 0, jnp.inf, self.capacity(x))

    def is_open(self, segment):
        return False

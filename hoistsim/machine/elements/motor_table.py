"""A motor given by its torque-speed table: piecewise linear, continued linearly beyond its ends."""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from ._knots import interval
from ._motor import AbstractMotor


class TableMotor(AbstractMotor):
    """C(omega) from a table of (speed, torque), speeds strictly increasing.

    Between two rows the torque is linear; below the first row and above the last
    the first and last intervals' lines go on (a motor dragged backwards gives
    more torque, one driven past its last row brakes), so the characteristic is
    continuous everywhere and the integrator sees no kink beyond the table.
    """

    table_speeds: object  # rad/s, strictly increasing, at least two
    table_torques: object  # N*m

    @classmethod
    def characteristic_from(cls, spec) -> dict:
        speeds, torques = zip(*spec.torque_speed)
        return {"table_speeds": np.asarray(speeds, float), "table_torques": np.asarray(torques, float)}

    def characteristic(self, speed):
        s, c = self.table_speeds, self.table_torques
        k = interval(speed, s)
        slope = (c[k + 1] - c[k]) / (s[k + 1] - s[k])
        return c[k] + slope * (speed - s[k])

    def speed_scale(self):
        return jnp.max(jnp.abs(self.table_speeds))

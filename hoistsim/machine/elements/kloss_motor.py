"""An induction motor by Kloss's formula: its torque against slip from its breakdown torque and slip."""

from __future__ import annotations

from ._motor import AbstractMotor


class KlossMotor(AbstractMotor):
    """T(s) = 2 T_b / (s / s_b + s_b / s), s = (omega_s - omega) / omega_s: zero at the synchronous speed,
    T_b at the breakdown slip s_b, 2 T_b s_b / (1 + s_b^2) at standstill; beyond the synchronous speed it brakes
    (a generator), below standstill (dragged backwards) it falls off again, as the formula does on both sides.
    Written 2 T_b s_b s / (s^2 + s_b^2), smooth through s = 0."""

    breakdown_torque: object  # T_b, N*m
    breakdown_slip: object  # s_b
    synchronous_speed: object  # omega_s, rad/s

    @classmethod
    def characteristic_from(cls, spec) -> dict:
        return {"breakdown_torque": spec.breakdown_torque, "breakdown_slip": spec.breakdown_slip,
                "synchronous_speed": spec.no_load_speed}

    def characteristic(self, speed):
        slip = 1.0 - speed / self.synchronous_speed
        return 2.0 * self.breakdown_torque * self.breakdown_slip * slip / (slip**2 + self.breakdown_slip**2)

    def speed_scale(self):
        return self.synchronous_speed

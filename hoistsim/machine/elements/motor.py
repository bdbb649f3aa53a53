"""A motor on a shaft: its characteristic's torque, its rotor's inertia, its work."""

from __future__ import annotations

from ..._pytree import static
from ._motor import AbstractMotor
from ._motor_variants import MOTOR_VARIANTS
from ._names import called
from ._shaft_work import AbstractShaftWork


class Motor(AbstractShaftWork):
    """A motor whose rotor turns with a shaft: its inertia joins the shaft's, its torque is its
    characteristic (linear, a torque-speed table or constant, ``law``) at the shaft's speed.  Its work is a
    state and a work term of the ledger; outputs ``<name>_torque`` and ``<name>_work`` (the hoist's motor,
    on the shaft ``motor``: ``motor_torque``, ``motor_work``)."""

    law: AbstractMotor  # the characteristic and the rotor's inertia
    shaft: str = static("")
    section: str = static("")  # the motor's name

    @classmethod
    def from_spec(cls, spec) -> "Motor":
        kind = MOTOR_VARIANTS[spec.characteristic]
        return cls(law=kind(inertia=spec.moment_of_inertia, **kind.characteristic_from(spec)), shaft=spec.shaft,
                   section=spec.name)

    @property
    def columns(self) -> dict:
        motor = called("motor", self.section)
        return {f"{self.section}_torque": ("N*m", f"torque of {motor} on shaft {self.shaft}, from its characteristic"),
                f"{self.section}_work": ("J", f"work done by {motor} so far")}

    def torque(self, x):
        return self.law.characteristic(x.speed(self.shaft))

    def inertias(self) -> tuple:
        return ((self.shaft, self.law.inertia),)

    def speed_scale(self):
        return self.law.speed_scale()

    def outputs(self, x) -> dict:
        return {f"{self.section}_torque": self.torque(x), f"{self.section}_work": x.state(self.work_state)}

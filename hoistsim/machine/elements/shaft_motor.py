"""A motor on a shaft of a drawn drivetrain: the hoist motor's characteristic, on the shaft the user names."""

from __future__ import annotations

from ..._pytree import static
from ._motor import AbstractMotor
from ._shaft_work import AbstractShaftWork


class ShaftMotor(AbstractShaftWork):
    """A motor whose rotor turns with a shaft: its inertia joins the shaft's, its torque is its
    characteristic (linear, a torque-speed table or constant: the hoist's motor variants, ``law``) at the
    shaft's speed.  Its work is a state and a work term of the ledger; outputs ``<name>_torque`` and
    ``<name>_work``."""

    law: AbstractMotor  # the characteristic and the rotor's inertia (its own shaft unused)
    shaft: str = static("")
    section: str = static("")  # the motor's name in drivetrain.motors

    # A drawn part's builder, called by Drivetrain.from_spec with the motor's name: not yet the registry's
    # (spec, scenario), which it takes once the registry builds drawn parts too.
    @classmethod
    def from_spec(cls, name: str, spec, variants: dict) -> "ShaftMotor":
        kind = variants[spec.characteristic]
        law = kind(inertia=spec.moment_of_inertia, initial_speed=0.0, **kind.characteristic_from(spec))
        return cls(law=law, shaft=spec.shaft, section=name)

    @property
    def columns(self) -> dict:
        return {f"{self.section}_torque": ("N*m", f"torque of motor {self.section} on shaft {self.shaft}"),
                f"{self.section}_work": ("J", f"work done by motor {self.section} so far")}

    def torque(self, x):
        return self.law.characteristic(x.speed(self.shaft))

    def inertias(self) -> tuple:
        return ((self.shaft, self.law.inertia),)

    def speed_scale(self):
        return self.law.speed_scale()

    def outputs(self, x) -> dict:
        return {f"{self.section}_torque": self.torque(x), f"{self.section}_work": x.state(self.work_state)}

"""What every motor characteristic shares: the motor shaft, its inertia, its work."""

from __future__ import annotations

import abc
from typing import ClassVar

from ..core.element import AbstractElement


class AbstractMotor(AbstractElement):
    """The drive motor on its own shaft (the body ``motor``); subclasses give the torque-speed law.

    Brings the body with its inertia and initial speed, the torque
    ``characteristic(speed)``, the work it does (a state, the ledger's work in)
    and its output columns.
    """

    inertia: object  # kg*m^2, rotor and whatever else turns with it
    initial_speed: object  # rad/s

    section: ClassVar[str] = "motor"
    summaries: ClassVar[dict] = {"final_motor_speed": "rad/s"}
    ledger_kinds: ClassVar[dict] = {"motor_work": "work"}
    columns: ClassVar[dict] = {
        "motor_speed": ("rad/s", "motor shaft speed (side a of the clutch)"),
        "motor_torque": ("N*m", "motor torque from its characteristic"),
        "motor_work": ("J", "work done by the motor so far"),
    }

    @abc.abstractmethod
    def characteristic(self, speed):
        """Motor torque (N*m) at shaft speed ``speed`` (rad/s)."""

    @classmethod
    def from_spec(cls, spec, scenario) -> "AbstractMotor":
        return cls(inertia=spec.moment_of_inertia, initial_speed=scenario.initial.motor_speed,
                   **cls.characteristic_from(spec))

    @classmethod
    @abc.abstractmethod
    def characteristic_from(cls, spec) -> dict:
        """The characteristic's fields from the motor section."""

    def bodies(self) -> dict:
        return {"motor": self.initial_speed}

    def inertias(self) -> tuple:
        return (("motor", self.inertia),)

    def torques(self, x) -> tuple:
        return (("motor", self.characteristic(x.speed("motor"))),)

    def states(self) -> dict:
        return {"motor_work": 0.0}

    def rates(self, x) -> dict:
        speed = x.speed("motor")
        return {"motor_work": self.characteristic(speed) * speed}

    def ledger(self, x) -> dict:
        return {"motor_work": x.state("motor_work")}

    def outputs(self, x) -> dict:
        speed = x.speed("motor")
        return {"motor_speed": speed, "motor_torque": self.characteristic(speed),
                "motor_work": x.state("motor_work")}

    def summary(self, x) -> dict:
        return {"final_motor_speed": x.speed("motor")}

"""The motor's characteristics by the name the schema gives them (the hoist's motor, a drivetrain's motors)."""

from __future__ import annotations

from .constant_torque_motor import ConstantTorqueMotor
from .kloss_motor import KlossMotor
from .linear_motor import LinearMotor
from .motor_table import TableMotor

MOTOR_VARIANTS = {"linear": LinearMotor, "kloss": KlossMotor, "torque_speed": TableMotor,
                  "torque": ConstantTorqueMotor}

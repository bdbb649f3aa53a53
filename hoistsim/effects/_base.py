"""What an effect may contribute to a run."""

from __future__ import annotations

import abc
from typing import ClassVar

import equinox as eqx

from .._pytree import pytree_dataclass


class RowContext(eqx.Module):
    """The state of the machine at output rows (arrays, one entry per row), for effects' outputs."""

    time: object  # s
    motor_speed: object  # rad/s
    output_speed: object  # rad/s, pinion shaft
    motor_acceleration: object  # rad/s^2
    output_acceleration: object  # rad/s^2
    motor_torque: object  # N*m
    clutch_torque: object  # N*m, through the clutch, positive when the motor drives
    engagement_force: object  # N
    drum_held: object  # bool


class AbstractEffect:
    """An optional part of the machine, selected by its YAML section.

    Subclasses declare their traced numbers as annotated fields; each becomes a
    frozen dataclass and a JAX pytree when it is defined.

    Contributions (all optional; the defaults contribute nothing):
    - ``boundaries``: scheduled times at which the dynamics change; the
      integration stops and restarts there instead of searching for them;
    - ``holds_drum``: whether the effect keeps the drum shaft still at a time;
    - ``boundary_events``: event kinds to record at a boundary;
    - ``outputs``: extra time series, with ``output_units``.
    """

    section: ClassVar[str]
    output_units: ClassVar[dict[str, str]] = {}

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        pytree_dataclass(cls)

    @classmethod
    @abc.abstractmethod
    def from_spec(cls, spec, scenario) -> "AbstractEffect":
        ...

    def boundaries(self) -> tuple:
        return ()

    def holds_drum(self, t):
        """A boolean (array) if this effect can hold the drum, else None."""
        return None

    def boundary_events(self, t) -> tuple:
        """(kind, happens_at_t) pairs for the scheduled events of this effect."""
        return ()

    def outputs(self, row: RowContext, drivetrain) -> dict:
        return {}

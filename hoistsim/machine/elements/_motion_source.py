"""What a prescribed motion shares, a speed's, an angle's or an acceleration's: a drive holding a shaft to it."""

from __future__ import annotations

import abc
from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import AbstractCoupling
from ._shaft_work import AbstractWorkOnShaft
from ._signal import signal_fields, signal_tables


class AbstractMotionSource(AbstractWorkOnShaft, AbstractCoupling):
    """A coupling of the shaft ``self.shaft`` to the ground that is always stuck and holds the shaft at the motion
    ``motion(x)`` gives (a drive: the core solves for the torque that takes, and keeps the speed it holds where
    couplings lock or a boundary is passed).  The torque it applies to the shaft is its output
    ``<section>_torque``; its work on the shaft (that torque times the shaft's speed, and its impulses' work where
    the speed it holds jumps) is the state ``<section>_work`` and a work term of the energy ledger.  Subclasses
    say what the reference (``reference``, a signal of time: a speed, an angle or an acceleration, in a mass's units
    on a line) holds the shaft at."""

    reference_times: object  # s
    reference_values: object  # rad/s, rad or rad/s^2 (m/s, m or m/s^2 on a line)
    reference_amplitudes: object
    reference_frequencies: object  # Hz
    reference_phases: object  # rad
    reference_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    reference_envelope_values: object = None
    filter_frequency: object = None  # Hz: Modelica's f_crit (None: exactly)
    on_line: bool = static(False)  # it drives a mass (m, m/s, m/s^2; a force)
    shaft: str = static("")
    section: str = static("")  # its key in drivetrain.motion_sources

    can_slip: ClassVar[bool] = False
    reports_switches: ClassVar[bool] = False
    drives: ClassVar[bool] = True

    @classmethod
    def from_spec(cls, spec) -> "AbstractMotionSource":
        return cls(**signal_fields(spec.reference, "reference"), filter_frequency=spec.filter_frequency,
                   on_line=spec.resolved("on_line"), shaft=spec.shaft, section=spec.name)

    def tables(self) -> dict:
        return signal_tables(self, "reference")

    @abc.abstractmethod
    def motion(self, x) -> tuple:
        """(the shaft's speed it holds, or None: the speed it has; its acceleration), rad/s and rad/s^2."""

    @property
    def torque_name(self) -> str:
        """Its output: ``<name>_torque`` on a shaft, ``<name>_force`` on a mass."""
        return f"{self.section}_{'force' if self.on_line else 'torque'}"

    @property
    def columns(self) -> dict:
        what, units, body = ("force", "N", "mass") if self.on_line else ("torque", "N*m", "shaft")
        return {self.torque_name: (units, f"{what} the motion source {self.section} applies to {body} {self.shaft}, "
                                          "positive in its positive sense")}

    def joins(self) -> tuple:
        return (self.shaft, None)

    def capacity(self, x):
        return jnp.inf

    def sliding_torque(self, x):
        return 0.0

    def torque(self, x):
        """What it applies to the shaft (N*m): the opposite of what the shaft passes into it."""
        return -x.coupling_torque(self.section)

    def outputs(self, x) -> dict:
        return {self.torque_name: self.torque(x)}

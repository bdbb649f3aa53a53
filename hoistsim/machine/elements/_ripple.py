"""What a torque ripple is: a torque periodic in a shaft's angle, and the work it does."""

from __future__ import annotations

import math
from typing import ClassVar

import jax.numpy as jnp
import numpy as np

from ..._pytree import static
from ..core.element import AbstractElement
from ._knots import interpolate, interval
from ._names import NamedOutputs


class AbstractRipple(NamedOutputs, AbstractElement):
    """A torque periodic in the angle of a shaft: harmonics, or one period as a table.

    ``form`` "harmonics": sum of A_k sin(k 2 pi theta / period + phi_k);
    ``form`` "table": piecewise linear over one period, repeated.  Its work from
    the start, the integral of the torque over the angle turned, is exact (a
    closed form, not a state), so the energy ledger holds to round-off.
    """

    period: object  # rad
    orders: object  # harmonics: k, amplitudes (N*m), phases (rad); empty for a table
    amplitudes: object
    phases: object
    table_angles: object  # rad, 0 .. period; empty for harmonics
    table_torques: object  # N*m
    form: str = static("harmonics")
    shaft: str = static("")  # the shaft whose angle it follows and on which it acts
    part: str = static("")  # the name of the part it belongs to (a motor, a shaft)

    key: ClassVar[str]  # its key in its part: its name is <part>.<key> (the hoist's motor.ripple)
    direction: ClassVar[float]  # +1: drives the shaft; -1: resists it
    work_pattern: ClassVar[str]  # its work's name in the energy ledger, a pattern of its part's name
    column_pattern: ClassVar[str]  # its output column (the ripple torque, positive in its own sense)
    meaning: ClassVar[str]  # what its column is

    @classmethod
    def of_part(cls, ripple, shaft: str, spec) -> "AbstractRipple":
        """The ripple ``ripple`` (a RippleSpec) of the part ``spec``, on ``shaft``."""
        return cls(**cls.fields_from(ripple), shaft=shaft, part=spec.name)

    @property
    def section(self) -> str:  # a name of its own: its kinks are found by it
        return f"{self.part}.{self.key}"

    @property
    def part_name(self) -> str:
        return self.part

    @property
    def work_term(self) -> str:
        return self.named(self.work_pattern)

    @property
    def column(self) -> str:
        return self.named(self.column_pattern)

    @property
    def ledger_kinds(self) -> dict:
        return {self.work_term: "work"}

    @property
    def columns(self) -> dict:
        return {self.column: ("N*m", self.meaning.format(shaft=self.shaft))}

    def angles(self) -> tuple:
        return (self.shaft,)

    def kinks(self, x) -> dict:
        return {"knots": self.knots_passed(x.angle(self.shaft))} if self.kink_names() else {}

    def torques(self, x) -> tuple:
        return ((self.shaft, self.direction * self.torque_at(x.angle(self.shaft))),)

    def ledger(self, x) -> dict:
        return {self.work_term: self.direction * self.work_to(x.angle(self.shaft))}

    def outputs(self, x) -> dict:
        return {self.column: self.torque_at(x.angle(self.shaft))}

    @staticmethod
    def fields_from(spec) -> dict:
        empty = np.zeros((0,))
        if spec.table is not None:
            angles, torques = (np.asarray(column, float) for column in zip(*spec.table))
            return {"period": spec.period, "orders": empty, "amplitudes": empty, "phases": empty,
                    "table_angles": angles, "table_torques": torques, "form": "table"}
        return {"period": spec.period, "orders": np.asarray([h.order for h in spec.harmonics], float),
                "amplitudes": np.asarray([h.amplitude for h in spec.harmonics], float),
                "phases": np.asarray([h.phase for h in spec.harmonics], float),
                "table_angles": empty, "table_torques": empty, "form": "harmonics"}

    def kink_names(self) -> tuple:
        return ("knots",) if self.form == "table" else ()

    def knots_passed(self, angle):
        """The table's knots counted along the angle: a whole number exactly at each knot."""
        n = self.table_angles.shape[0] - 1  # knots per period, the last one the next period's first
        turns = jnp.floor(angle / self.period)
        return turns * n + interpolate(angle - turns * self.period, self.table_angles, jnp.arange(n + 1.0))

    def torque_at(self, angle):
        """The ripple torque (N*m) at a shaft angle (rad)."""
        if self.form == "harmonics":
            rate = self.orders * (2 * math.pi / self.period)
            return jnp.sum(self.amplitudes * jnp.sin(rate * angle + self.phases))
        return interpolate(jnp.mod(angle, self.period), self.table_angles, self.table_torques)

    def work_to(self, angle):
        """Integral of the ripple torque from angle 0 to ``angle`` (J)."""
        if self.form == "harmonics":
            rate = self.orders * (2 * math.pi / self.period)
            return jnp.sum(self.amplitudes / rate * (jnp.cos(self.phases) - jnp.cos(rate * angle + self.phases)))
        a, m = self.table_angles, self.table_torques
        cumulative = jnp.concatenate([jnp.zeros(1), jnp.cumsum(0.5 * (m[1:] + m[:-1]) * jnp.diff(a))])
        turns = jnp.floor(angle / self.period)
        rest = angle - turns * self.period
        i = interval(rest, a)
        into = rest - a[i]
        slope = (m[i + 1] - m[i]) / (a[i + 1] - a[i])
        return turns * cumulative[-1] + cumulative[i] + m[i] * into + 0.5 * slope * into**2

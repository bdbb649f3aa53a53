"""A slider-crank on a shaft (the hoist's motor shaft): a reciprocating mass whose inertia varies with the crank angle."""

from __future__ import annotations

from typing import ClassVar

import jax
import jax.numpy as jnp

from ..._pytree import static
from ..core.element import AbstractElement
from ._names import NamedOutputs


class SliderCrank(NamedOutputs, AbstractElement):
    """Mass m at the end of a rod l on a crank r keyed to a shaft (the hoist's ``reciprocating``: the motor shaft).

    The slider sits at x(a) = r cos a + sqrt(l^2 - r^2 sin^2 a) (exact
    kinematics, a the crank angle from the outer dead centre); its kinetic
    energy 1/2 m (dx/dt)^2 = 1/2 I(a) w^2 with I(a) = m (dx/da)^2.  With an
    inertia that varies, the equation of motion is I w' + 1/2 I'(a) w^2 = M:
    the element brings I(a) to its shaft and the torque -1/2 I'(a) w^2.
    That torque does no work of its own over the motion (the kinetic energy
    1/2 I(a) w^2 already holds what it moves), so it has no ledger term.
    """

    mass: object  # kg
    crank_radius: object  # m
    rod_length: object  # m
    shaft: str = static("motor")
    section: str = static("")  # its name

    inertia_varies: ClassVar[bool] = True

    @classmethod
    def from_spec(cls, spec) -> "SliderCrank":
        return cls(mass=spec.mass, crank_radius=spec.crank_radius, rod_length=spec.rod_length, shaft=spec.shaft,
                   section=spec.name)

    @property
    def columns(self) -> dict:
        return {self.named("{name}_position"): ("m", f"slider distance from the crank axis ({self.section})"),
                self.named("{name}_inertia"): ("kg*m^2", f"inertia of the reciprocating mass at shaft {self.shaft}, "
                                                         "m (dx/da)^2")}

    def position(self, angle):
        """Slider distance from the crank axis (m) at crank angle ``angle`` (rad)."""
        r, l = self.crank_radius, self.rod_length
        return r * jnp.cos(angle) + jnp.sqrt(l**2 - (r * jnp.sin(angle)) ** 2)

    def velocity_ratio(self, angle):
        """dx/da (m/rad): the slider's speed per unit crank speed."""
        r, l = self.crank_radius, self.rod_length
        s = jnp.sin(angle)
        return -r * s - r**2 * s * jnp.cos(angle) / jnp.sqrt(l**2 - (r * s) ** 2)

    def inertia_at(self, angle):
        """(I, dI/da) of the reciprocating mass at the crank (kg*m^2, kg*m^2/rad)."""
        ratio, ratio_slope = jax.jvp(self.velocity_ratio, (angle,), (jnp.ones_like(angle),))
        return self.mass * ratio**2, 2.0 * self.mass * ratio * ratio_slope

    def angles(self) -> tuple:
        return (self.shaft,)

    def varying_inertias(self, angle) -> tuple:
        return ((self.shaft, *self.inertia_at(angle(self.shaft))),)

    def torques(self, x) -> tuple:
        _, slope = self.inertia_at(x.angle(self.shaft))
        return ((self.shaft, -0.5 * slope * x.speed(self.shaft) ** 2),)

    def outputs(self, x) -> dict:
        angle = x.angle(self.shaft)
        return {self.named("{name}_position"): self.position(angle),
                self.named("{name}_inertia"): self.inertia_at(angle)[0]}

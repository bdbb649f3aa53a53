"""A slider-crank on the motor shaft: a reciprocating mass whose inertia varies with the crank angle."""

from __future__ import annotations

from typing import ClassVar

import jax
import jax.numpy as jnp

from ..core.element import AbstractElement


class SliderCrank(AbstractElement):
    """reciprocating: mass m at the end of a rod l on a crank r keyed to the motor shaft.

    The slider sits at x(a) = r cos a + sqrt(l^2 - r^2 sin^2 a) (exact
    kinematics, a the crank angle from the outer dead centre); its kinetic
    energy 1/2 m (dx/dt)^2 = 1/2 I(a) w^2 with I(a) = m (dx/da)^2.  With an
    inertia that varies, the equation of motion is I w' + 1/2 I'(a) w^2 = M:
    the element brings I(a) to the motor shaft and the torque -1/2 I'(a) w^2.
    That torque does no work of its own over the motion (the kinetic energy
    1/2 I(a) w^2 already holds what it moves), so it has no ledger term.
    """

    mass: object  # kg
    crank_radius: object  # m
    rod_length: object  # m

    section: ClassVar[str] = "reciprocating"
    inertia_varies: ClassVar[bool] = True
    columns: ClassVar[dict] = {
        "slider_position": ("m", "slider distance from the crank axis"),
        "reciprocating_inertia": ("kg*m^2", "inertia of the reciprocating mass at the motor shaft, m (dx/da)^2"),
    }

    @classmethod
    def from_spec(cls, spec, scenario) -> "SliderCrank":
        return cls(mass=spec.mass, crank_radius=spec.crank_radius, rod_length=spec.rod_length)

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
        return ("motor",)

    def varying_inertias(self, angle) -> tuple:
        return (("motor", *self.inertia_at(angle("motor"))),)

    def torques(self, x) -> tuple:
        _, slope = self.inertia_at(x.angle("motor"))
        return (("motor", -0.5 * slope * x.speed("motor") ** 2),)

    def outputs(self, x) -> dict:
        angle = x.angle("motor")
        return {"slider_position": self.position(angle), "reciprocating_inertia": self.inertia_at(angle)[0]}

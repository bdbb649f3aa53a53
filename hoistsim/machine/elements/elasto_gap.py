"""A spring-damper that only pushes: a buffer, a stop with give (Modelica's ElastoGap)."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from .spring_damper import SpringDamper


class ElastoGap(SpringDamper):
    """A spring-damper whose sides touch only while it is compressed (its strain, the twist or the distance less
    the unstretched one, below zero): there tau_c = c strain < 0 and tau = tau_c + max(tau_c, d w_rel) while that
    pushes (< 0), else 0: it never pulls, and its damping never exceeds its spring's own force (Modelica's law,
    its exponent n = 1).

    Contact and separation are found by root-finding on the pushing force's negative,
    min(-c strain, -(c strain + d w_rel)): events ``contact`` and ``separation``, named after the part.  With
    damping, where the damping's force stops being limited to the spring's (a kink of the law) is a row,
    ``gap_damping_limit``, and so is its unstretched length passed outwards, ``gap_edge`` (where what a separation
    lets go of the strain is spent: Modelica's event).  Ledger: the strain energy 1/2 tau_c^2 / c while
    compressed, and what the damper and a separation shed, (tau - tau_c) w_rel >= 0.  Output ``<name>_contact``:
    1 while its sides touch, else 0.
    """

    damped: bool = static(False)  # a damping is given: where it stops being limited is a row

    observation_kinds: ClassVar[tuple] = ("gap_contact", "gap_damping_limit", "gap_edge")
    crossings: ClassVar[tuple] = ("gap_contact",)
    crossing_events: ClassVar[dict] = {"gap_contact": ("contact", "separation")}

    @classmethod
    def from_spec(cls, spec) -> "ElastoGap":
        return cls(**cls.fields_from(spec), damped=spec.damping > 0.0)

    @property
    def columns(self) -> dict:
        return {**super().columns, f"{self.section}_contact": ("1", f"1 while {self.section}'s sides touch")}

    def pushing(self, x):
        """The force it pushes its sides apart with, were they touching: -(c strain + d w_rel), the lesser of that
        and its spring's part -c strain; positive where they touch."""
        spring = self.stiffness * self.strain(x)
        return jnp.minimum(-spring, -(spring + self.damping * self.twist_speed(x)))

    def stored_strain(self, x):
        return jnp.minimum(self.strain(x), 0.0)

    def torque(self, x):
        spring = self.stiffness * self.stored_strain(x)
        return jnp.where(self.pushing(x) > 0.0, spring + jnp.maximum(spring, self.damping * self.twist_speed(x)),
                         0.0)

    def loss_power(self, x):
        # what it passes less what its spring stores: the damper's heat, and the strain a separation lets go
        return (self.torque(x) - self.stiffness * self.stored_strain(x)) * self.twist_speed(x)

    def observes(self, kind: str) -> bool:
        return kind not in ("gap_damping_limit", "gap_edge") or self.damped

    def observations(self, x) -> dict:
        # touching, the damping's force is limited to the spring's until it rises above it (a kink of the law: a
        # row, so that no step straddles it); positive from the contact on until then
        spring = self.stiffness * self.stored_strain(x)
        limited = jnp.where(self.pushing(x) > 0.0, spring - self.damping * self.twist_speed(x), 1.0)
        # its unstretched length passed outwards, where the strain a separation lets go is spent (the strain
        # energy's kink; inwards it is the contact, found as such): positive while compressed
        return {"gap_contact": self.pushing(x), "gap_damping_limit": limited, "gap_edge": -self.strain(x)}

    def outputs(self, x) -> dict:
        touching = (self.pushing(x) > 0.0).astype(jnp.int8)
        return {**super().outputs(x), f"{self.section}_contact": touching}

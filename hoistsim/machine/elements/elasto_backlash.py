"""A spring-damper with play: gear teeth, a coupling with slack (Modelica's ElastoBacklash)."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from .spring_damper import SpringDamper


class ElastoBacklash(SpringDamper):
    """A spring-damper whose sides are apart while its strain (twist less unstretched angle) is within the play
    +-b/2, and pressed beyond it: tau_c = c (strain -+ b/2), and tau = tau_c + min(tau_c, d w_rel) while that
    presses (> 0 beyond +b/2, < 0 beyond -b/2), 0 otherwise: the damping never pulls the sides together, nor
    exceeds the spring's own torque (Modelica's law).

    Contact and separation on either side are found by root-finding on
    min(c (strain - b/2), c (strain - b/2) + d w_rel) (and its mirror): events ``contact`` and
    ``separation``, named after the part.  Ledger: the strain energy 1/2 tau_c^2 / c, and what the damper
    and a release shed, (tau - tau_c) w_rel >= 0.  With damping, where the damping's torque stops being
    limited to the spring's (a kink of the law) is a row, ``backlash_damping_limit``; so is each crossing of
    the play's edges inwards, ``backlash_edge`` (where a release ends: Modelica's events; outwards, and without
    damping either way, the edge is the contact or the separation).  Output ``<name>_contact``: 1 pressed forwards (beyond
    +b/2), -1 backwards, 0 apart.
    """

    half_play: object = 0.0  # b/2, rad
    damped: bool = static(False)  # a damping is given: where it stops being limited is a row

    observation_kinds: ClassVar[tuple] = ("backlash_forward", "backlash_backward", "backlash_damping_limit",
                                          "backlash_edge")
    crossings: ClassVar[tuple] = ("backlash_forward", "backlash_backward", "backlash_edge")
    crossing_events: ClassVar[dict] = {"backlash_forward": ("contact", "separation"),
                                       "backlash_backward": ("contact", "separation")}

    @classmethod
    def from_spec(cls, spec) -> "ElastoBacklash":
        return cls(**cls.fields_from(spec), half_play=0.5 * spec.backlash, damped=spec.damping > 0.0)

    @property
    def columns(self) -> dict:
        return {**super().columns, f"{self.section}_contact": (
            "1", f"1 while {self.section}'s sides press forwards (beyond +b/2), -1 backwards, 0 apart")}

    def pressing(self, x):
        """(forwards, backwards): c (strain - b/2) + d w_rel beyond +b/2, and the negative of its mirror, each
        the lesser of that and its spring's part: positive where that side presses."""
        strain, damping = self.strain(x), self.damping * self.twist_speed(x)
        ahead, behind = self.stiffness * (strain - self.half_play), self.stiffness * (strain + self.half_play)
        return jnp.minimum(ahead, ahead + damping), jnp.minimum(-behind, -(behind + damping))

    def stored_strain(self, x):
        strain = self.strain(x)
        return jnp.where(strain > self.half_play, strain - self.half_play,
                         jnp.where(strain < -self.half_play, strain + self.half_play, 0.0))

    def torque(self, x):
        spring = self.stiffness * self.stored_strain(x)
        damping = self.damping * self.twist_speed(x)
        forwards, backwards = self.pressing(x)
        return jnp.where(forwards > 0.0, spring + jnp.minimum(spring, damping),
                         jnp.where(backwards > 0.0, spring + jnp.maximum(spring, damping), 0.0))

    def loss_power(self, x):
        # what it passes less what its spring stores: the damper's heat, and the strain a release lets go
        return (self.torque(x) - self.stiffness * self.stored_strain(x)) * self.twist_speed(x)

    def observes(self, kind: str) -> bool:
        # undamped, its contact and separation are where the edges are crossed: the edges add no guard of their own
        return kind not in ("backlash_damping_limit", "backlash_edge") or self.damped

    def observations(self, x) -> dict:
        forwards, backwards = self.pressing(x)
        # pressed, the damping's torque is limited to the spring's until it falls below it (a kink of the law:
        # a row, so that no step straddles it); positive from the contact on until then
        damping = self.damping * self.twist_speed(x)
        spring = self.stiffness * self.stored_strain(x)
        limited = jnp.where(forwards > 0.0, damping - spring, jnp.where(backwards > 0.0, spring - damping, 1.0))
        # the sides' edges, where the spring's strain begins (the strain energy's kink, a release's end); moving
        # outwards, the edge is where the sides meet (their contact, found as such), and a second guard on that
        # same root would end a pass a few ulps after the first: there it keeps its sign and crosses nothing
        strain = self.strain(x)
        edge = jnp.abs(strain) - self.half_play
        outwards = jnp.sign(strain) * self.twist_speed(x) > 0.0
        edge = jnp.where(outwards, jnp.sign(edge), edge)
        return {"backlash_forward": forwards, "backlash_backward": backwards, "backlash_damping_limit": limited,
                "backlash_edge": edge}

    def outputs(self, x) -> dict:
        forwards, backwards = self.pressing(x)
        contact = jnp.where(forwards > 0.0, 1, jnp.where(backwards > 0.0, -1, 0)).astype(jnp.int8)
        return {**super().outputs(x), f"{self.section}_contact": contact}

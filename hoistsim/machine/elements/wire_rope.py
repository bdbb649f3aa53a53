"""A wire rope whose stiffness follows its free length: k = E A / L."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ._rope import AbstractRope, damping, initial_stretch

# Below this fraction of its free length at the start the rope is taken as wound up: the run has
# already recorded ``rope_wound_up`` (an error), and the stiffness stops growing without end.
WOUND_UP = 1e-3


class WireRope(AbstractRope):
    """A wire rope of axial stiffness E A (modulus times metallic area): k = E A / L with L = L_0 - x_d,
    the free length between the drum and the load, shortening as the drum winds rope on.

    A stiffness that changes with the length wound on is not a conservative
    spring: at a fixed stretch, winding rope on raises the strain energy
    1/2 k s^2 by 1/2 k' s^2 per metre wound.  That energy is a work term of
    the ledger of its own (``rope_stiffening``), so the balance still closes.
    ``rope_wound_up``: the free length has reached zero (the scenario's
    free_length is too short for what the drum winds on).
    """

    axial_stiffness: object  # E A, N
    free_length: object  # L_0, m

    observation_kinds: ClassVar[tuple] = AbstractRope.observation_kinds + ("rope_wound_up",)
    limits: ClassVar[tuple] = ("rope_wound_up",)
    errors: ClassVar[dict] = {"rope_wound_up": (
        "rope.free_length", "is too short: the drum has wound all of it on at t = {time:.4g} s (the load would "
        "reach the drum); give the rope's length from the drum to the load at the start")}
    ledger_kinds: ClassVar[dict] = {**AbstractRope.ledger_kinds, "rope_stiffening": "work"}
    columns: ClassVar[dict] = {**AbstractRope.columns,
                               "rope_stiffness": ("N/m", "rope stiffness E A / L at the free length L")}

    @classmethod
    def from_spec(cls, spec) -> "WireRope":
        rope, g = spec.rope, spec.resolved("gravity")
        axial = rope.modulus * rope.metallic_area
        k = axial / rope.free_length
        return cls(axial_stiffness=axial, free_length=rope.free_length, damping=damping(spec, k),
                   initial_stretch=initial_stretch(spec, g, k), weight=spec.mass * g)

    def length(self, x):
        """The free length L (m): what the drum has not wound on."""
        return self.free_length - self.wound(x)

    def stiffness(self, x):
        return self.axial_stiffness / jnp.maximum(self.length(x), WOUND_UP * self.free_length)

    def stiffness_rate(self, x):
        # dk/dt = E A / L^2 * dx_d/dt, the rope point's speed winding rope on
        return self.stiffness(x) ** 2 / self.axial_stiffness * x.speed("rope_point")

    def states(self) -> dict:
        return {**super().states(), "rope_stiffening": 0.0}

    def rates(self, x) -> dict:
        return {**super().rates(x), "rope_stiffening": 0.5 * self.stiffness_rate(x) * self.strain(x) ** 2}

    def ledger(self, x) -> dict:
        return {**super().ledger(x), "rope_stiffening": x.state("rope_stiffening")}

    def observations(self, x) -> dict:
        return {**super().observations(x), "rope_wound_up": self.length(x)}

    def outputs(self, x) -> dict:
        return {**super().outputs(x), "rope_stiffness": self.stiffness(x)}

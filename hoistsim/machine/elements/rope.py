"""An elastic rope of constant stiffness."""

from __future__ import annotations

from ._rope import AbstractRope, damping, initial_stretch


class Rope(AbstractRope):
    """The rope as a spring of one stiffness k (N/m) and its damper, whatever the length paid out."""

    constant_stiffness: object  # k, N/m

    @classmethod
    def from_spec(cls, spec) -> "Rope":
        k, g = spec.rope.stiffness, spec.resolved("gravity")
        return cls(constant_stiffness=k, damping=damping(spec, k), initial_stretch=initial_stretch(spec, g, k),
                   weight=spec.mass * g)

    def stiffness(self, x):
        return self.constant_stiffness

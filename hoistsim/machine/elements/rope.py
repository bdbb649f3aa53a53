"""An elastic rope of constant stiffness."""

from __future__ import annotations

from ._rope import AbstractRope, damping, initial_stretch


class Rope(AbstractRope):
    """The rope as a spring of one stiffness k (N/m) and its damper, whatever the length paid out."""

    constant_stiffness: object  # k, N/m

    @classmethod
    def from_spec(cls, spec, scenario) -> "Rope":
        k = spec.stiffness
        return cls(constant_stiffness=k, damping=damping(scenario, k), initial_stretch=initial_stretch(scenario, k),
                   weight=scenario.load.mass * scenario.gravity)

    def stiffness(self, x):
        return self.constant_stiffness

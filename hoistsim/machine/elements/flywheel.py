"""A flywheel keyed to a shaft: inertia and nothing else."""

from __future__ import annotations

from ..._pytree import static
from ..core.element import AbstractElement


class Flywheel(AbstractElement):
    """Adds its inertia to the shaft it is keyed to: a drawn drivetrain's rotor; the hoist's flywheel (on
    ``motor`` or ``drum``) and its drum.

    Given as an inertia or as a rim of density rho, width s and radii R_o, R_i:
    I = pi rho s (R_o^4 - R_i^4) / 2 (the seed's formula), worked out on loading.
    """

    inertia: object  # kg*m^2
    shaft: str = static("motor")
    section: str = static("flywheel")  # its name: the flywheel, or a rotor the hoist's template keys (the drum)

    @classmethod
    def from_spec(cls, spec) -> "Flywheel":
        return cls(inertia=spec.moment_of_inertia, shaft=spec.shaft, section=spec.name)

    def inertias(self) -> tuple:
        return ((self.shaft, self.inertia),)

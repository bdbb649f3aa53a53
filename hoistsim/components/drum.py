"""The winch drum."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Drum:
    diameter: float  # d, m
    inertia: float  # I, kg*m^2

    @property
    def rope_radius(self) -> float:
        """R = d/2 (m): the rope leaves the drum at this radius."""
        return 0.5 * self.diameter

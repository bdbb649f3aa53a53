"""The hanging load."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class HangingLoad:
    mass: float  # M, kg
    gravity: float  # g, m/s^2

    @property
    def weight(self) -> float:
        """P = M g (N)."""
        return self.mass * self.gravity

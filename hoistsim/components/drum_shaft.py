"""The drum shaft on its two bearings: reactions to the tooth and rope forces.

Geometry of exercise 6, along the shaft: the gear wheel overhangs bearing A by
``gear_offset`` (on the side away from B), the rope leaves the drum
``rope_offset`` from A towards B, and bearing B is ``span`` from A.  The radial
tooth force N and the rope tension P act in the same plane and the same sense
(the exercise's yz plane); the tangential tooth force T acts in the other (xz).
Moments about A give B's reaction, the force balance A's.  Written with plain
arithmetic so that it serves floats, numpy and traced JAX arrays alike.
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class DrumShaft:
    gear_offset: float  # a, m
    rope_offset: float  # m
    span: float  # m

    def reactions(self, tangential, radial, rope_tension) -> dict:
        """Bearing reactions (N) for tooth forces T (tangential), N (radial) and rope tension P.

        Components follow the exercise's signs: y in the plane of N and P,
        x in the plane of T; magnitudes are the vector sums.
        """
        a, r, span = self.gear_offset, self.rope_offset, self.span
        b_y = (rope_tension * r - radial * a) / span
        a_y = radial + rope_tension - b_y
        b_x = -tangential * a / span
        a_x = tangential - b_x
        return {
            "bearing_A_x": a_x,
            "bearing_A_y": a_y,
            "bearing_A": (a_x**2 + a_y**2) ** 0.5,
            "bearing_B_x": b_x,
            "bearing_B_y": b_y,
            "bearing_B": (b_x**2 + b_y**2) ** 0.5,
        }

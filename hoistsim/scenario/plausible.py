"""What real parts measure: the ranges outside which a scenario's value is warned of (an error under
--strict).  Wide on purpose: a value outside is no design but a unit forgotten (``drum: diameter: 40``, a
40 m drum) or a slip of the keyboard (a wire rope of 0.04 mm^2)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .units import Dimension, to_si


@dataclass(frozen=True)
class Plausible:
    """Metadata of a quantity field: the range a real part's value lies in (``low`` and ``high`` with their
    units, ``what`` names the quantity: "a hoist drum's diameter").  A value outside is accepted with a
    warning, an error under --strict: a 40 m drum is a unit forgotten, not a design."""

    low: str
    high: str
    what: str

    def holds(self, x: float, dimension: Dimension) -> bool:
        """Whether the SI value ``x`` lies in the range (zero, where a key allows it, means "none": it does)."""
        return x == 0 or to_si(self.low, dimension) <= abs(x) <= to_si(self.high, dimension)

    def example(self, dimension: Dimension) -> str:
        """How a value of the key is written (in messages, in the reference): the dimension's example where
        this range holds it ('20 cm' for a drum's diameter), else a typical value, the range's geometric
        middle to one figure in the unit of its low end ('4 mm' for a gear's module, never '20 cm')."""
        if self.holds(to_si(dimension.example.strip("'"), dimension), dimension):
            return dimension.example
        unit = self.low.split(maxsplit=1)[1]
        middle = math.sqrt(to_si(self.low, dimension) * to_si(self.high, dimension)) / to_si(f"1 {unit}", dimension)
        return f"'{float(f'{middle:.1g}'):g} {unit}'"


GEAR_MODULE = Plausible("0.3 mm", "50 mm", "a gear's module")
HOIST_DRUM_DIAMETER = Plausible("50 mm", "5 m", "a hoist drum's diameter")
CLUTCH_FACE_RADIUS = Plausible("10 mm", "1 m", "a clutch face's radius")
HOIST_LOAD = Plausible("1 kg", "1000 t", "a hoist's load")
GEAR_WHEEL_PITCH_DIAMETER = Plausible("20 mm", "5 m", "a gear wheel's pitch diameter")
DRUM_RADIUS = Plausible("25 mm", "2.5 m", "a drum's radius")
MOTOR_SPEED = Plausible("10 rpm", "30000 rpm", "a motor's speed")
ROTOR_RADIUS_OF_GYRATION = Plausible("5 mm", "2 m", "a rotor's radius of gyration")
FLYWHEEL_RIM_DIAMETER = Plausible("50 mm", "10 m", "a flywheel rim's diameter")
FLYWHEEL_RIM_WIDTH = Plausible("5 mm", "2 m", "a flywheel rim's width")
CRANK_RADIUS = Plausible("5 mm", "5 m", "a crank's radius")
CONNECTING_ROD_LENGTH = Plausible("10 mm", "20 m", "a connecting rod's length")
DRUM_SHAFT_LENGTHS = Plausible("5 mm", "10 m", "a drum shaft's lengths")
WIRE_ROPE_METALLIC_AREA = Plausible("1 mm^2", "5000 mm^2", "a wire rope's metallic area")
ROPE_FREE_LENGTH = Plausible("0.1 m", "3000 m", "a rope's free length")
SHAFT_DIAMETER = Plausible("2 mm", "2 m", "a shaft's diameter")
SHAFT_LENGTH = Plausible("5 mm", "100 m", "a shaft's length")

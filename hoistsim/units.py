"""Physical quantities in scenario files: "200 daN", "300 rpm", "25 deg" -> SI floats.

A bare number is already SI (angles in radians, speeds in rad/s).  Strings are
parsed by pint and converted once, at load time, to the SI unit of the quantity
the key expects; a string of the wrong dimension is an error that says what was
expected and what was given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import pint


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    # pint's registry is costly to build; one per process is enough.
    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    return ureg


@dataclass(frozen=True)
class Dimension:
    """What a scenario key measures: a readable name and its SI unit."""

    name: str
    si_unit: str


TORQUE = Dimension("torque", "N*m")
ANGULAR_SPEED = Dimension("angular speed", "rad/s")
INERTIA = Dimension("moment of inertia", "kg*m^2")
MASS = Dimension("mass", "kg")
LENGTH = Dimension("length", "m")
ANGLE = Dimension("angle", "rad")
FORCE = Dimension("force", "N")
TIME = Dimension("time", "s")
ACCELERATION = Dimension("acceleration", "m/s^2")
DIMENSIONLESS = Dimension("pure number", "")


class UnitError(ValueError):
    """A value that is not a quantity of the expected dimension."""


def to_si(value: object, dimension: Dimension) -> float:
    """Convert a scenario value to a float in the SI unit of ``dimension``.

    Accepts ints, floats and strings with units.  Booleans, lists and other
    types are rejected: they are never a physical quantity.
    """
    if isinstance(value, bool) or value is None:
        raise UnitError(f"expected a {dimension.name}, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise UnitError(f"expected a {dimension.name}, got {type(value).__name__} {value!r}")
    ureg = registry()
    text = value.strip()
    try:
        quantity = ureg.Quantity(text)
    except Exception as exc:  # pint raises several unrelated types for bad text
        raise UnitError(f"cannot read {value!r} as a {dimension.name} ({_first_line(exc)})") from None
    if not isinstance(quantity, ureg.Quantity):  # a plain number written as a string
        quantity = ureg.Quantity(float(quantity), "")
    target = ureg.Unit(dimension.si_unit) if dimension.si_unit else ureg.dimensionless
    if quantity.dimensionality != target.dimensionality:
        raise UnitError(
            f"expected a {dimension.name} (like {_example(dimension)}), got {value!r} "
            f"which is a {_describe(quantity.dimensionality)}"
        )
    return float(quantity.to(target).magnitude)


def is_finite(x: float) -> bool:
    return math.isfinite(x)


def _first_line(exc: Exception) -> str:
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


def _describe(dimensionality) -> str:
    text = str(dimensionality)
    return "pure number" if text in ("", "dimensionless") else text


_EXAMPLES = {
    "torque": "'500 N*m'",
    "angular speed": "'300 rpm'",
    "moment of inertia": "'40 kg*m^2'",
    "mass": "'500 kg'",
    "length": "'20 cm'",
    "angle": "'25 deg'",
    "force": "'200 daN'",
    "time": "'0.5 s'",
    "acceleration": "'9.81 m/s^2'",
    "pure number": "0.3",
}


def _example(dimension: Dimension) -> str:
    return _EXAMPLES.get(dimension.name, dimension.si_unit)

"""Physical quantities in scenario files: "200 daN", "300 rpm", "25 deg" -> SI floats.

A bare number is already SI (angles in radians, speeds in rad/s, temperatures in
kelvin).  Strings are
parsed by pint and converted once, at load time, to the SI unit of the quantity
the key expects; a string of the wrong dimension is an error that says what was
expected and what was given, in an engineer's words (:mod:`.unit_words`: "500 Nm"
is no newton metre to pint, "0,3" is 0).  NaN and infinities are never accepted.

pint treats the radian as dimensionless, so "25 deg" would pass for a friction
coefficient and "5 Hz" for an angular speed.  Here the radian counts as a
dimension of its own whenever a unit is written: an angle needs an angle unit,
an angular speed needs an angle per time ("rpm", "rad/s"), a pure number none.

Also here: whole-number counts and text, the other values a scenario holds, and
the pydantic field types built on them that the schema uses (tables of
quantities are :mod:`.tables`').  Every problem is a :class:`UnitError` (a
``ValueError``), which pydantic reports at the key's location.
"""

from __future__ import annotations

import math
import re
import sys
from dataclasses import dataclass
from functools import lru_cache, partial
from typing import TYPE_CHECKING, Annotated, Any, get_args

from pydantic import BeforeValidator

from ..cache_folders import cache_folder
from . import unit_words as words
from .dimensions import (  # noqa: F401 (each dimension, read as units.<NAME> throughout the schema)
    ACCELERATION,
    ANGLE,
    ANGULAR_ACCELERATION,
    ANGULAR_SPEED,
    AREA,
    CONDUCTANCE,
    DAMPING,
    DENSITY,
    DIMENSIONLESS,
    FORCE,
    FREQUENCY,
    HEAT_CAPACITY,
    INERTIA,
    LENGTH,
    MASS,
    POWER,
    PRESSURE,
    STIFFNESS,
    TEMPERATURE,
    TIME,
    TORQUE,
    TORSIONAL_DAMPING,
    TORSIONAL_STIFFNESS,
    VELOCITY,
    Dimension,
)
from .unit_factors import known_factors

if TYPE_CHECKING:
    import pint


def _pint():
    """pint, imported where a unit is first read (a scenario of bare SI numbers never needs it).

    pint imports Dask at its own import when Dask is installed, to recognise
    Dask arrays of quantities, which hoistsim never makes: 80 ms of every
    command's start.  Dask is hidden while pint is imported, unless it is
    already there.
    """
    if "pint" in sys.modules:
        return sys.modules["pint"]
    hidden = "dask" not in sys.modules
    if hidden:
        sys.modules["dask"] = None  # importlib's "not installed" mark
    try:
        import pint
    finally:
        if hidden:
            del sys.modules["dask"]
    return pint


@lru_cache(maxsize=1)
def registry() -> pint.UnitRegistry:
    # pint's registry is costly to build (0.12 s): one per process, its parsed definitions kept on disk (0.04 s).
    pint = _pint()
    try:
        ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True, cache_folder=cache_folder("pint"))
    except Exception:  # pint writes its cache in place: another process's half-written file
        ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("@alias revolution = rev")  # "3 rev/s"
    return ureg


class UnitError(ValueError):
    """A value that is not a quantity of the expected kind, or not an allowed one."""


def _shown(value: object) -> str:
    """The value as the user wrote it."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return f"{value:g}"
    return repr(value)


def to_si(value: object, dimension: Dimension) -> float:
    """Convert a scenario value to a finite float in the SI unit of ``dimension``.

    Accepts ints, floats and strings with units.  Booleans, lists and other
    types are rejected: they are never a physical quantity.
    """
    try:
        if isinstance(value, str):  # sweeps validate the same strings thousands of times
            return _string_to_si(value, dimension)
        return _to_si(value, dimension)
    except OverflowError:  # an integer too large for a float
        raise UnitError(f"must be a finite number, got {_shown(value)[:40]}") from None
    except UnitError:
        if dimension.line is None or not isinstance(value, str):
            raise
        try:  # a part on a line: its value in the line's units
            return _string_to_si(value, dimension.line)
        except UnitError:
            pass
        raise


@lru_cache(maxsize=4096)
def _string_to_si(value: str, dimension: Dimension) -> float:
    # "6543.21 N": the number times the unit's SI value, that unit judged once (a sweep lists thousands
    # of forces in a few units; pint reads each in ~60 us); anything else is pint's to read
    match = _NUMBER_UNIT.fullmatch(value)
    if match:
        factor = _unit_factor(match.group(2), dimension)
        if factor is not None:
            return _finite(float(match.group(1)) * factor, value)
    return _to_si(value, dimension)


_NUMBER_UNIT = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z_][A-Za-z_*/^\d]*)\s*")


@lru_cache(maxsize=None)
def _unit_factor(unit: str, dimension: Dimension) -> float | None:
    """What one ``unit`` is in the SI unit of ``dimension``; None where pint must read the whole text
    (a unit of another dimension, an unknown one, one with an offset).  Kept on disk once pint has said."""
    known = known_factors()
    key = known.key(unit, dimension.si_unit, dimension.radians)
    if key in known.factors:
        return known.factors[key]
    try:
        one = _to_si(f"1 {unit}", dimension)
        multiplicative = registry().Quantity(1, unit)._is_multiplicative
    except Exception:  # pint's errors, our UnitError: the full reading says what is wrong
        return None
    if not multiplicative:
        return None
    known.learn(key, one)
    return one


def _to_si(value: object, dimension: Dimension) -> float:
    expected = f"expected {words.a(dimension.name)} (like {dimension.example})"
    if value is None:
        raise UnitError(f"no value given; {expected}")
    if isinstance(value, bool):
        raise UnitError(f"{expected}, got the yes/no value {_shown(value)}")
    if isinstance(value, (int, float)):
        return _finite(float(value), value)
    if not isinstance(value, str):
        kind = {list: "a list", dict: "a mapping"}.get(type(value), f"a {type(value).__name__}")
        shown = repr(value) if isinstance(value, (list, dict)) else str(value)
        raise UnitError(f"{expected}, got {kind}: {shown}")
    text = value.strip()
    if not re.search(r"\d|nan|inf", text, re.IGNORECASE):
        raise UnitError(f"{expected}, got {value!r} (no number in it)")
    if re.search(r"[\d)]\s*(\*\*|\^)", text):  # pint would compute 10**10**10 in full
        raise UnitError(f"{expected}, got {value!r}: write powers of ten as 1e6, not with ^ or **")
    comma = words.decimal_comma(text)  # pint reads "1,5" as 15
    if comma:
        raise UnitError(f"{expected}, got {value!r}: {comma}")
    if ":" in text:  # pint reads "100 kg:900 kg" as a product
        raise UnitError(f"{expected}, got {value!r}: one value, without ':' (a range of values is a sweep's: "
                        "KEY=FROM:TO:COUNT on the command line, {from: ..., to: ..., count: ...} in a file's sweep:)")
    ureg = registry()
    fits = partial(_fits, dimension=dimension)
    try:
        quantity = ureg.Quantity(text)
    except _pint().UndefinedUnitError as exc:
        names = ", ".join(repr(n) for n in exc.args) or "a name"
        raise UnitError(words.unknown_unit(value, names, expected, fits)) from None
    except Exception:  # pint raises several unrelated types for bad text
        raise UnitError(f"{expected}, cannot read {value!r}") from None
    if str(quantity.units) == "dimensionless":  # a plain number in a string: SI
        return _finite(float(quantity.magnitude), value)
    radians, target = _radians(quantity), _target(dimension)
    if quantity.dimensionality != target.dimensionality or radians != dimension.radians:
        angle_missing = bool(dimension.radians) and quantity.dimensionality == target.dimensionality
        raise UnitError(words.wrong_kind(value, quantity, radians, dimension, expected, fits, angle_missing))
    return _finite(float(quantity.to(target).magnitude), value)


def _radians(quantity) -> int:
    """The power of the angle in a quantity's unit (pint counts the radian as no dimension)."""
    return int(registry().get_root_units(quantity.units)[1]._units.get("radian", 0))


def _target(dimension: Dimension):
    """The SI unit of a dimension, as pint's."""
    ureg = registry()
    return ureg.Unit(dimension.si_unit) if dimension.si_unit else ureg.dimensionless


def _fits(text: str, dimension: Dimension) -> bool:
    """Whether pint reads ``text`` as a quantity of the kind ``dimension`` is (a spelling to suggest)."""
    try:
        quantity = registry().Quantity(text)
    except Exception:  # pint's errors: it does not
        return False
    return quantity.dimensionality == _target(dimension).dimensionality and _radians(quantity) == dimension.radians


def _finite(x: float, value: object) -> float:
    if not math.isfinite(x):
        raise UnitError(f"must be a finite number, got {_shown(value)}")
    return x


def show(x: float, dimension: Dimension) -> str:
    """An SI value in words for messages: ``1.5708`` (angle) -> ``'90 deg'``."""
    unit = dimension.shown_in or dimension.si_unit
    if unit and unit != dimension.si_unit:
        x = registry().Quantity(x, dimension.si_unit).to(unit).magnitude
    return f"{x:.6g} {unit}".strip()


def check_range(x: float, value: object, dimension: Dimension, *, gt: float | None = None,
                ge: float | None = None, lt: float | None = None, le: float | None = None,
                hint: str = "") -> float:
    """Check an SI value against its physical limits; the message names them in the user's terms."""
    problem = None
    if gt is not None and not x > gt:
        positive = "must be above absolute zero (0 K)" if dimension is TEMPERATURE else "must be positive"
        problem = positive if gt == 0 else f"must be more than {show(gt, dimension)}"
    elif ge is not None and not x >= ge:
        problem = "must not be negative" if ge == 0 else f"must be at least {show(ge, dimension)}"
    elif lt is not None and not x < lt:
        problem = f"must be less than {show(lt, dimension)}"
    elif le is not None and not x <= le:
        problem = f"must be at most {show(le, dimension)}"
    if problem is None:
        return x
    if isinstance(value, str):
        got = _shown(value)
    else:  # a bare number is SI; say so, and in the usual unit where that differs
        got = f"{x:.6g} {dimension.si_unit}".strip()
        got += f" (= {show(x, dimension)})" if dimension.shown_in else ""
    raise UnitError(f"{problem}{hint}, got {got}")


def count(value: object, what: str, minimum: int = 1) -> int:
    """A whole number (teeth, friction surfaces): ``17`` or ``17.0``, never ``17.5`` or ``true``."""
    whole = None
    if isinstance(value, int) and not isinstance(value, bool):
        whole = value
    elif isinstance(value, float) and value.is_integer():
        whole = int(value)
    if whole is None:
        raise UnitError(f"must be a whole number of {what}, got {_shown(value)}")
    if whole < minimum:
        raise UnitError(f"must be at least {minimum}, got {whole}")
    return whole


# --------------------------------------------------------------------------------------
# the value types of the scenario schema (pydantic fields)


@dataclass(frozen=True)
class Limits:
    """Metadata of a quantity field: the limits ``check_range`` holds it to (SI), for the scenario reference."""

    gt: float | None = None
    ge: float | None = None
    lt: float | None = None
    le: float | None = None


def quantity(dimension: Dimension, hint: str = "", plausible: Any = None, **limits: float):
    """A float field given as a number (SI) or text with units, checked against ``limits`` (gt, ge, lt, le);
    ``plausible``: the range outside which a value is warned of."""

    def convert(value: Any) -> float:
        return check_range(to_si(value, dimension), value, dimension, hint=hint, **limits)

    # the dimension, the limits and the plausible range ride along as metadata, for what reads the schema (the
    # notes on bare numbers and implausible values, the reference)
    extra = (plausible,) if plausible is not None else ()
    return Annotated[float, BeforeValidator(convert), dimension, Limits(**limits), *extra]


def metadata_of(field, kind: type) -> Any:
    """The first metadata of ``kind`` on a field of the schema (a pydantic FieldInfo), or on the first member
    of its union that has one (an optional quantity, ``quantity(...) | None``, keeps it there), or None."""
    found = [m for m in field.metadata if isinstance(m, kind)]
    for member in get_args(field.annotation):
        found += [m for m in getattr(member, "__metadata__", ()) if isinstance(m, kind)]
    return found[0] if found else None


def dimension_of(field) -> Dimension | None:
    """The dimension of a quantity field of the schema, or None."""
    return metadata_of(field, Dimension)


def bare_number_read_as(value: object, dimension: Dimension) -> str | None:
    """How a bare number on a key with a unit is read ("40 m", "31.4 rad/s (299.8 rpm)"), or None where no
    unit was forgotten: a pure number, a value with its unit, zero (zero in any unit)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) or value == 0 or not dimension.si_unit:
        return None
    read = f"{value:g} {dimension.si_unit}"
    if dimension is TEMPERATURE:
        return f"{read} ({show(value, dimension)})"
    if dimension.radians == 1:
        shown = value * (30 / math.pi if dimension.shown_in == "rpm" else 180 / math.pi)
        return f"{read} ({shown:.4g} {dimension.shown_in})"
    return read


@dataclass(frozen=True)
class Count:
    """Metadata of a whole-number field: what it counts and its least value, for the scenario reference."""

    what: str
    minimum: int


def whole(what: str, minimum: int = 1):
    """An int field that counts ``what`` ("teeth")."""
    return Annotated[int, BeforeValidator(lambda value: count(value, what, minimum)), Count(what, minimum)]


def _text(value: Any, required: bool = True) -> str:
    if not isinstance(value, str) and not (value is None and not required):
        raise UnitError(f"must be text, got {value!r} (put it in quotes)")
    if required and not value.strip():
        raise UnitError("must not be empty")
    return value or ""


Text = Annotated[str, BeforeValidator(_text)]
FreeText = Annotated[str, BeforeValidator(lambda value: _text(value, required=False))]


def range_ends(start: object, stop: object) -> tuple[float, float, str]:
    """The ends of a sweep range as magnitudes in the unit of ``start`` ('' for bare numbers)."""
    if isinstance(start, (int, float)) and not isinstance(start, bool) and \
            isinstance(stop, (int, float)) and not isinstance(stop, bool):
        return float(start), float(stop), ""
    ureg = registry()
    try:
        first, last = ureg.Quantity(str(start)), ureg.Quantity(str(stop))
    except Exception as exc:  # pint's parse errors
        raise UnitError(f"cannot make a range from {start!r} to {stop!r} ({str(exc).splitlines()[0]})") from None
    if first.dimensionality != last.dimensionality:  # a bare end with an end in units, or two kinds
        kinds = [words.kind_of(q.dimensionality, _radians(q)) or f"quantity in {q.units}" for q in (first, last)]
        raise UnitError(f"cannot make a range from {str(start)!r} to {str(stop)!r}: the ends are {words.a(kinds[0])} "
                        f"and {words.a(kinds[1])}; {_both_in_units(first, last)}")
    last = last.to(first.units)
    if not (math.isfinite(first.magnitude) and math.isfinite(last.magnitude)):
        raise UnitError(f"the range ends must be finite, got {start!r} and {stop!r}")
    written = _NUMBER_UNIT.fullmatch(str(start))  # the unit as the user wrote it ("N*m", not pint's "m * N")
    return float(first.magnitude), float(last.magnitude), written.group(2) if written else f"{first.units:~}"


def _both_in_units(first, last) -> str:
    """How to write a range whose ends differ in kind: the bare end given the other's unit, where one is bare."""
    if first.unitless == last.unitless:
        return "write both in units of the key's kind"
    unit = f"{(last if first.unitless else first).units:~}"
    return f"write both with their unit, like {first.magnitude:g} {unit}:{last.magnitude:g} {unit}"


def si_line(unit: str) -> tuple[float, float]:
    """(factor, offset): a magnitude in ``unit`` is factor * magnitude + offset in SI base units (the offset
    is zero but for temperatures: 20 degC is 293.15 K, not 20 * 274.15 K)."""
    ureg = registry()
    zero = float(ureg.Quantity(0.0, unit).to_base_units().magnitude)
    return float(ureg.Quantity(1.0, unit).to_base_units().magnitude) - zero, zero

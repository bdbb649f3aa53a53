"""The words of an error on a value's unit: what pint read, in an engineer's terms, and how to write what was
meant.

pint reads some common shop spellings as something else, or as nothing: "500 Nm" is 500 number_meter (a
count per length, a [length] / [mass] to pint), not a newton metre; "40 kgm2" is an unknown unit; "0,3" is 0
and "1,5 kg" is 15 kg (a comma is taken for a thousands separator).  Each is refused (never read as pint
reads it) and said in the writer's terms: what was read, and how to write what was meant.  A dimension pint
prints in brackets is named as an engineer names it ("[mass] * [length] / [time] ** 2" is a force).
"""

from __future__ import annotations

import re

# dimensionality (as pint prints it, radian power) -> what an engineer calls it
KINDS = {
    ("[mass] * [length] ** 2 / [time] ** 2", 0): "torque (or energy)",
    ("[mass] * [length] / [time] ** 2", 0): "force",
    ("[mass] * [length] ** 2", 0): "moment of inertia",
    ("[mass]", 0): "mass",
    ("[length]", 0): "length",
    ("[length] ** 2", 0): "area",
    ("[length] ** 3", 0): "volume",
    ("[time]", 0): "time",
    ("1 / [time]", 0): "frequency",
    ("1 / [time]", 1): "angular speed",
    ("[length] / [time]", 0): "speed",
    ("[length] / [time] ** 2", 0): "acceleration",
    ("[mass] / [length] / [time] ** 2", 0): "pressure",
    ("[mass] / [time] ** 2", 0): "stiffness",
    ("[mass] * [length] ** 2 / [time] ** 2", -1): "torsional stiffness",
    ("[mass] * [length] ** 2 / [time]", -1): "torsional damping",
    ("[mass] * [length] ** 2 / [time] ** 3", 0): "power",
    ("[temperature]", 0): "temperature",
    ("[mass] * [length] ** 2 / [temperature] / [time] ** 2", 0): "heat capacity",
    ("[mass] * [length] ** 2 / [temperature] / [time] ** 3", 0): "thermal conductance",
    ("dimensionless", 0): "pure number",
    ("dimensionless", 1): "angle",
}


def kind_of(dimensionality, radians: int) -> str | None:
    """What an engineer calls a dimension ("force"), or None for one with no name ("[mass] * [length]")."""
    return KINDS.get((str(dimensionality) or "dimensionless", radians))


def a(noun: str) -> str:
    """The noun with its article: "an angle", "a mass"."""
    return f"an {noun}" if noun[:1] in "aeiou" else f"a {noun}"


# a number written with a comma: "0,3", "1,5 kg", "1,500 kg" (never a list: a YAML list is split before this)
_COMMA_NUMBER = re.compile(r"([-+]?\d+),(\d+)")

# spellings pint reads as another unit or none, and the spelling meant; each applied to the unit's text
_RESPELLINGS = (
    # Nm, kNm, daNm, mNm (and "Nms", which pint reads as a plural of Nm): newton metres
    (re.compile(r"(?<![A-Za-z])(da|[kMGm]?)Nm(s?)(?![A-Za-z])"),
     lambda m: f"{m[1]}N*m" + ("*s" if m[2] else "")),
    # kgm2, kgm^2, kgm²: kilogram square metres; kgm: a kilogram metre
    (re.compile(r"(?<![A-Za-z])kgm(?:\^?2|²)"), lambda m: "kg*m^2"),
    (re.compile(r"(?<![A-Za-z])kgm(?![A-Za-z\d^²])"), lambda m: "kg*m"),
    # deg for a temperature: pint's deg is the angle's degree (suggested only where a temperature is wanted)
    (re.compile(r"(?<![A-Za-z])deg(?![A-Za-z])"), lambda m: "degC"),
    # mm2, m3, cm2: a power written without its ^
    (re.compile(r"(?<![A-Za-z])(mm|cm|dm|km|m)([23])(?![\d.])"), lambda m: f"{m[1]}^{m[2]}"),
)

_NUMBER = re.compile(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?\s*")


def decimal_comma(text: str) -> str | None:
    """How to write a number given with a comma (``'1,5 kg'``), or None where there is none: a comma is
    never read (pint takes it for a thousands separator, "1,5" for 15)."""
    match = _COMMA_NUMBER.search(text)
    if match is None:
        return None
    point = _COMMA_NUMBER.sub(r"\1.\2", text.strip(), count=1)
    said = f"write decimals with a point, {point}"
    if len(match[2]) == 3:  # "1,500": perhaps thousands
        thousands = _COMMA_NUMBER.sub(r"\1\2", text.strip(), count=1)
        said += f", and thousands without a separator, {thousands}"
    return said


def respelt(text: str) -> tuple[str, str] | None:
    """(the unit as written, as meant) for a value written in a spelling pint reads otherwise (``'500 Nm'``:
    ``('Nm', 'N*m')``), or None."""
    number = _NUMBER.match(text)
    unit = text[number.end():] if number else text
    meant = unit
    for pattern, replace in _RESPELLINGS:
        meant = pattern.sub(replace, meant)
    return (unit.strip(), meant.strip()) if meant != unit else None


def with_unit(text: str, unit: str) -> str:
    """The value ``text`` with its number and ``unit``: ``('500 Nm', 'N*m')`` -> ``'500 N*m'``."""
    number = _NUMBER.match(text)
    return f"{number.group().strip()} {unit}" if number else unit


def spaced(unit: str) -> str:
    """A product of units also written with spaces: ``'N*m'`` -> ``'N*m (or N m)'``; others as they are."""
    if "*" in unit and "/" not in unit and "^" not in unit:
        return f"{unit} (or {unit.replace('*', ' ')})"
    return unit


def wrong_kind(value: str, quantity, radians: int, dimension, expected: str, fits, angle_missing: bool) -> str:
    """The error on ``value`` (pint's ``quantity``, the angle to the power ``radians`` in it) where its key
    wants another kind (``dimension``, said in ``expected``); ``fits(text)``: whether text is of that kind;
    ``angle_missing``: the value is of the kind but for an angle unit ("5 Hz" for a speed).  A known misspelling
    is said as such, a dimension without a name with what pint read and the unit of the key's kind."""
    meant = _meant(value, fits)
    if meant:
        return f"{expected}, got {value!r}: {meant[0]!r} is read as {quantity.units}, not {meant[1]}; " + meant[2]
    kind = kind_of(quantity.dimensionality, radians)
    if kind is None:
        unit = dimension.shown_in or dimension.si_unit
        how = f"write it in {spaced(unit)}" if unit else "write it as a plain number"
        return (f"{expected}, got {value!r}, read as {quantity.magnitude:g} {quantity.units}, which is no "
                f"{dimension.name}: {how}, like {dimension.example}")
    hint = f"; write it with an angle unit, like {dimension.example}" if angle_missing else ""
    return f"{expected}, got {value!r} which is {a(kind)}{hint}"


def unknown_unit(value: str, names: str, expected: str, fits) -> str:
    """The error on ``value`` whose unit pint does not know: a known misspelling's spelling where it has one."""
    meant = _meant(value, fits)
    return f"{expected}, got {value!r}: unknown unit {names}" + (f": {meant[2]}" if meant else "")


def _meant(value: str, fits) -> tuple[str, str, str] | None:
    """(the unit as written, as meant, how to write it) for a value in a spelling pint reads otherwise, where
    the spelling meant is of the key's kind (``fits``); else None."""
    found = respelt(value.strip())
    if found is None or not fits(with_unit(value, found[1])):
        return None
    return found[0], found[1], f"write {spaced(found[1])}, like {with_unit(value, found[1])!r}"

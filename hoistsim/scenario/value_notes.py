"""Values a scenario accepts that may not say what was meant: a bare number on a key with a unit, a value far
outside what its part measures.

A bare number is SI (the rule), so ``drum: diameter: 40`` is a 40 m drum: accepted, and said, one line per key
with its file and line, how the number was read and how to write its unit.  A value outside its key's
:class:`~.units.Plausible` range (a 40 m drum, a 0.04 mm^2 rope), with its unit or without, is said too.
``strict`` loading makes them errors, every one raised at once (``--strict`` on the command line).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from pydantic import BaseModel

from ..errors import ScenarioError
from . import tables
from . import units as u
from .plausible import Plausible
from .keys import field_at, members_of, model_of
from .schema import Scenario
from .yamlsource import line_of

# what each key of a signal given in harmonics measures (None: the signal's own dimension)
_HARMONIC_KEYS = {"amplitude": None, "frequency": u.FREQUENCY, "phase": u.ANGLE}


def value_notes(raw: dict, tree: Any, source: str, overridden: frozenset[str] = frozenset()) -> list[ScenarioError]:
    """One note for each key whose value may not say what was meant, each naming the key, its file and line
    (a key set by --set: that option)."""
    notes = []
    for path, note in _section_notes(raw, Scenario, ()):
        dotted = ".".join(map(str, path))
        where = ("--set", None) if dotted in overridden else (source, line_of(tree, path))
        notes.append(ScenarioError(dotted, note, source=where[0], line=where[1]))
    return notes


def swept_notes(key: str, spec, numbers: np.ndarray, tree: Any, source: str) -> list[ScenarioError]:
    """The notes on a swept key's values as written (``spec``: a list, or a range's from/to/count), each value's
    SI number in ``numbers`` (NaN: a table): the first bare number, the first implausible value.  ``tree``
    None: the sweep came from the command line."""
    field = field_at(key)
    dimension = u.dimension_of(field) if field is not None else None
    if dimension is None or not dimension.si_unit:
        return []
    is_range = isinstance(spec, dict)
    # a range's values between its ends are numbers it worked out: only its ends are as the user wrote them
    written = [(end, spec.get(end), None) for end in ("from", "to")] if is_range else \
        [(f"item {i + 1}", value, i) for i, value in enumerate(spec)]
    found = [next(((name, value, i) for name, value, i in written if u.bare_number_read_as(value, dimension)), None)]
    plausible = u.metadata_of(field, Plausible)
    if plausible is not None:
        low, high = u.to_si(plausible.low, dimension), u.to_si(plausible.high, dimension)
        size = np.abs(np.asarray(numbers, dtype=float))
        wrong = np.flatnonzero((size != 0) & ((size < low) | (size > high)))
        if wrong.size:
            i = int(wrong[0])
            # a value the range worked out is shown in SI, as a value with its unit (never a bare number)
            found.append((f"value {i + 1} of the range", u.show(float(numbers[i]), dimension), i) if is_range
                         else (f"item {i + 1}", spec[i], i))
    notes, said = [], set()
    for name, value, i in filter(None, found):
        if name in said:
            continue
        said.add(name)
        x = float(numbers[i]) if i is not None else u.to_si(value, dimension)
        note = _scalar_note(value, x, dimension, plausible)
        path = ("sweep", key, *((i,) if not is_range else ()))
        notes.append(ScenarioError(f"sweep.{key}", f"{name}: {note}", source=source,
                                   line=line_of(tree, path) if tree is not None else None))
    return notes


def _section_notes(data: dict, model: type[BaseModel], path: tuple):
    for key, value in data.items():
        field = model.model_fields.get(key)
        if field is None or (model is Scenario and key == "sweep"):
            continue
        members = members_of(model, key)
        if members is not None:
            named = value.items() if isinstance(value, dict) else enumerate(value or ())
            for name, entry in named:
                if isinstance(entry, dict):
                    yield from _section_notes(entry, members[1], (*path, key, name))
            continue
        sub = model_of(model, key)
        if sub is not None:
            if isinstance(value, dict):
                yield from _section_notes(value, sub, (*path, key))
            continue
        note = _value_note(value, field)
        if note:
            yield (*path, key), note


def _value_note(value: Any, field) -> str | None:
    """What a key's value may not mean: a scalar, a table's rows, a signal given in harmonics."""
    dimension = u.dimension_of(field)
    if isinstance(value, list):
        columns = _columns_of(field, dimension)
        for i, row in enumerate(value):
            for entry, column in zip(row if isinstance(row, list) else (), columns):
                read = u.bare_number_read_as(entry, column)
                if read:
                    return f"row {i + 1}: {_bare(entry, read, column.example)}"
        return None
    if dimension is None:
        return None
    if isinstance(value, dict):  # a signal in harmonics: its offset, each harmonic's amplitude, frequency, phase
        entries = [("offset", value.get("offset"), dimension)]
        for i, harmonic in enumerate(value.get("harmonics") or ()):
            entries += [(f"harmonic {i + 1}'s {name}", harmonic.get(name), of or dimension)
                        for name, of in _HARMONIC_KEYS.items() if isinstance(harmonic, dict)]
        for name, entry, of in entries:
            read = u.bare_number_read_as(entry, of)
            if read:
                return f"{name}: {_bare(entry, read, of.example)}"
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float, str)) or not dimension.si_unit:
        return None
    plausible = u.metadata_of(field, Plausible)
    if plausible is None and not u.bare_number_read_as(value, dimension):
        return None
    return _scalar_note(value, u.to_si(value, dimension), dimension, plausible)


def _scalar_note(value: Any, x: float, dimension: u.Dimension, plausible: Plausible | None) -> str | None:
    """A bare number's note, an implausible value's, or both in one sentence; None for neither."""
    read = u.bare_number_read_as(value, dimension)
    far = None
    if plausible is not None and not plausible.holds(x, dimension):
        far = f"far outside {plausible.what} ({plausible.low} to {plausible.high})"
    if read:
        example = plausible.example(dimension) if plausible is not None else dimension.example
        return _bare(value, read + (f", {far}" if far else ""), example)
    if far:
        return f"{u.show(x, dimension) if not isinstance(value, str) else value} is {far}: check it and its unit"
    return None


def _bare(value: Any, read: str, example: str) -> str:
    """A bare number's note: how it was read, and how to write its unit (``example``: a value of its key's)."""
    return f"the bare number {value:g} is read as {read}; write the unit, like {example}, to say which you mean"


def _columns_of(field, dimension: u.Dimension | None) -> list[u.Dimension]:
    """Each column's dimension of a table field: its Columns, a signal's (time, its dimension), or its first."""
    found = u.metadata_of(field, tables.Columns)
    if found is not None:
        return [of for _, of in found.columns]
    if dimension is not None:  # a signal's table: rows of time and the signal
        return [u.TIME, dimension]
    first = tables.first_column_of(field)
    return [first] if first is not None else []

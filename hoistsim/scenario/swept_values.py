"""A swept key's validated values, kept as arrays where they are numbers of one shape.

A sweep validates each of its values alone as the file is read and keeps what
each became (a float, a force table, a torque table) for building its runs.
Kept one Python object a value, a million force tables took some 570 bytes a
run (a pydantic model, two tuples, their floats): more than half a million-run
sweep's memory.  Kept as columns, a value takes its numbers' bytes; it is made
again, equal to the validated one, when a run asks for it.  Values that are not
numbers of one shape (words, tables of different lengths) stay a list.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from pydantic import BaseModel

# Values validated before they are stacked into columns: the most Python objects alive at once.
BATCH = 4096


class SweptValues(Sequence):
    """The values of one swept key: ``values[i]`` is the i-th as validated, ``stacked`` all of them at once
    (a model: each of its fields with a leading axis over the values; a number: an array), every number
    a float, as the elements built for a block's runs at once take them."""

    def __init__(self, kind, stacked):
        self.kind, self.stacked = kind, stacked

    def __len__(self) -> int:
        return _length(self.kind, self.stacked)

    def __getitem__(self, i):
        if isinstance(i, slice):
            return [self[k] for k in range(*i.indices(len(self)))]
        if not -len(self) <= i < len(self):
            raise IndexError(i)
        return _value(self.kind, self.stacked, i)


def collect(values) -> Sequence:
    """The validated ``values`` (an iterable: each is stacked as it comes, a batch at a time) as
    :class:`SweptValues`, or a list where they do not stack."""
    batches, pending, kind, plain = [], [], None, None
    for value in values:
        if plain is not None:
            plain.append(value)
            continue
        pending.append(value)
        if len(pending) == BATCH:
            kind, plain = _stacked_onto(batches, pending, kind)
            pending = []
    if plain is None and pending:
        kind, plain = _stacked_onto(batches, pending, kind)
    return plain if plain is not None else SweptValues(kind, _joined(kind, batches))


def _stacked_onto(batches: list, pending: list, kind):
    """(kind, None) with ``pending`` stacked onto ``batches`` (of ``kind``, None before the first); where it
    does not stack, (kind, every value so far as a list)."""
    this = _kind(pending[0])
    stacked = _stack(this, pending) if this is not None and kind in (None, this) else None
    if stacked is None or any(_value(this, stacked, k) != pending[k] for k in (0, len(pending) - 1)):
        return kind, [v for batch in batches for v in _values(kind, batch)] + pending
    batches.append(stacked)
    return this, None


def _kind(value):
    """How a value is rebuilt from its numbers: ``float``, ``int``, a tuple's ``("tuple", shape)``, a model's
    ``(Model, ((field, kind), ...))``; None where it holds no numbers of one shape."""
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, float):
        return float
    if isinstance(value, int):
        return int
    if isinstance(value, BaseModel):
        fields = tuple((name, _kind(getattr(value, name))) for name in type(value).model_fields)
        return None if any(k is None for _, k in fields) else (type(value), fields)
    if isinstance(value, tuple):
        shape = _shape(value)
        return None if shape is None else ("tuple", shape)
    return None


def _shape(value: tuple):
    """The shape of a tuple of floats (of tuples of floats, ...); None where it is ragged, empty or not floats."""
    if not value:
        return None
    if all(type(v) is float for v in value):
        return (len(value),)
    inner = [_shape(v) if isinstance(v, tuple) else None for v in value]
    if inner[0] is None or any(shape != inner[0] for shape in inner):
        return None
    return (len(value), *inner[0])


def _stack(kind, values: list):
    """``values``, all of ``kind``, as one value with a leading axis; None where one is not of it."""
    if kind in (float, int):  # whole numbers too as floats (elements take them so), while exact
        if any(type(v) is not kind or (kind is int and abs(v) > 2**53) for v in values):
            return None
        return np.asarray(values, dtype=float)
    if kind[0] == "tuple":  # numbers of the first value's shape (a value of another shape or type fails here)
        try:
            array = np.asarray(values, dtype=float)
        except (TypeError, ValueError):
            return None
        return array if array.shape == (len(values), *kind[1]) else None
    model, fields = kind
    if any(type(v) is not model for v in values):
        return None
    stacked = {}
    for name, field_kind in fields:
        stacked[name] = _stack(field_kind, [getattr(v, name) for v in values])
        if stacked[name] is None:
            return None
    return model.model_construct(**stacked)


def _value(kind, stacked, i: int):
    if kind is float:
        return float(stacked[i])
    if kind is int:
        return int(stacked[i])
    if kind[0] == "tuple":
        return _as_tuples(stacked[i])
    model, fields = kind
    return model.model_construct(**{name: _value(k, getattr(stacked, name), i) for name, k in fields})


def _as_tuples(array: np.ndarray):
    return tuple(_as_tuples(row) for row in array) if array.ndim > 1 else tuple(float(x) for x in array)


def _values(kind, stacked) -> list:
    return [_value(kind, stacked, i) for i in range(_length(kind, stacked))]


def _length(kind, stacked) -> int:
    if kind in (float, int) or kind[0] == "tuple":
        return len(stacked)
    model, fields = kind
    return _length(fields[0][1], getattr(stacked, fields[0][0]))


def _joined(kind, batches: list):
    if kind in (float, int) or kind[0] == "tuple":
        return np.concatenate(batches)
    model, fields = kind
    return model.model_construct(**{name: _joined(k, [getattr(b, name) for b in batches]) for name, k in fields})

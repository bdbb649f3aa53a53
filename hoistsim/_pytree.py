"""Frozen dataclasses that are JAX pytrees: cheap to build on the host by the thousand.

The plan of a run and its elements are built once per run of a sweep; an
equinox module costs ~75 us to construct, a registered frozen dataclass ~1 us.
Every field is data (a leaf or a subtree) unless it is declared with
:func:`static`: then it is part of the structure (a shaft's name, say), so two
values of it compile two programs.  A field the constructor does not take
(``init=False``, worked out from the others in ``__post_init__``) is neither:
it is made again wherever the pytree is unflattened.
"""

from __future__ import annotations

import dataclasses
import functools

import jax

from . import _jax  # noqa: F401  (float64 before any array exists)

_STATIC = "hoistsim_static"


def static(default=dataclasses.MISSING):
    """A field that is structure, not a traced number."""
    return dataclasses.field(default=default, metadata={_STATIC: True})


def pytree_dataclass(cls):
    """Make ``cls`` a frozen dataclass whose fields are pytree children, except the static ones (and those
    worked out at construction)."""
    cls = dataclasses.dataclass(frozen=True)(cls)
    fields = [f for f in dataclasses.fields(cls) if f.init]
    data = [f.name for f in fields if not f.metadata.get(_STATIC)]
    meta = [f.name for f in fields if f.metadata.get(_STATIC)]
    return jax.tree_util.register_dataclass(cls, data_fields=data, meta_fields=meta)


def static_values(obj) -> tuple:
    """The values of a pytree dataclass's static fields (its structure beside its class)."""
    return tuple(getattr(obj, name) for name in _static_names(type(obj)))


@functools.lru_cache(maxsize=None)
def _static_names(cls) -> tuple:
    return tuple(f.name for f in dataclasses.fields(cls) if f.metadata.get(_STATIC))

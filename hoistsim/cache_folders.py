"""Where hoistsim keeps what it can reuse between processes: compiled programs, which of them each command
was served (:mod:`hoistsim.program_hints`), pint's parsed units, each unit's SI factor as pint read it
(:class:`hoistsim.scenario.unit_factors.KnownFactors`).

HOISTSIM_CACHE_DIR, else ~/.cache/hoistsim/jax (the compiled programs' folder
kept its name; the others sit inside it).  HOISTSIM_CACHE_DIR set to an empty
string turns every cache off.  No JAX here: reading a scenario uses it.
"""

from __future__ import annotations

import contextlib
import os
import tempfile

CACHE_VARIABLE = "HOISTSIM_CACHE_DIR"


def cache_root() -> str | None:
    """The cache folder, or None where the user turned caching off."""
    directory = os.environ.get(CACHE_VARIABLE)
    if directory == "":
        return None
    return directory if directory is not None else os.path.join(os.path.expanduser("~"), ".cache", "hoistsim", "jax")


def cache_folder(name: str) -> str | None:
    """``name``'s folder in the cache, made if absent; None where caching is off or the folder cannot be made
    (a read-only home: run without it)."""
    root = cache_root()
    if root is None:
        return None
    folder = os.path.join(root, name)
    try:
        os.makedirs(folder, exist_ok=True)
    except OSError:
        return None
    return folder


def keep(path: str, data: bytes) -> None:
    """Write ``data`` at ``path`` in the cache whole or not at all: under a temporary name beside it, then
    renamed, so that two processes never read each other's half-written file (raises OSError: a full disk,
    a read-only cache; no temporary file is left)."""
    fd, tmp = tempfile.mkstemp(dir=os.path.dirname(path), suffix=".partial")
    try:
        with os.fdopen(fd, "wb") as handle:
            handle.write(data)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise

"""What a compiled program is made from besides its arguments: hoistsim's source and the libraries that trace it.

No JAX here: a stored program read in a thread while the command line starts is checked against it before
any of it is unpickled (:mod:`.stored_programs`).
"""

from __future__ import annotations

import functools
import hashlib
from pathlib import Path


@functools.lru_cache(maxsize=None)
def source_digest(package: str | None = None) -> str:
    """SHA-256 of every Python source of the package: a stored program is only as good as the code behind it.

    The version number does not change with an edit; the source does.  Read once
    per process (the package is ~100 kB).
    """
    root = Path(package or Path(__file__).resolve().parent)
    digest = hashlib.sha256()
    for path in sorted(root.rglob("*.py")):
        digest.update(str(path.relative_to(root)).encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()


@functools.lru_cache(maxsize=None)
def program_origin() -> tuple:
    """Our source's digest and the versions of the libraries that trace and run a program."""
    from importlib.metadata import version

    return (source_digest(), *(version(p) for p in ("jax", "jaxlib", "diffrax", "equinox", "optimistix")))

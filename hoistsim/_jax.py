"""JAX set-up: float64 before any array exists, and a persistent compilation cache.

Imported first by the package, so that every array hoistsim creates is float64.
"""

from __future__ import annotations

import os

# Equinox's runtime checks run as host callbacks, and XLA will not keep a
# program with host callbacks in the persistent cache.  With "nan" a failed
# check poisons the result instead; hoistsim checks each run's status and
# values explicitly.  Must be set before equinox is first imported.
os.environ.setdefault("EQX_ON_ERROR", "nan")

import jax  # noqa: E402

jax.config.update("jax_enable_x64", True)


def enable_compilation_cache() -> None:
    """Keep compiled solvers on disk, so a second `hoistsim run` skips compilation.

    The directory is HOISTSIM_CACHE_DIR, else ~/.cache/hoistsim/jax; setting
    HOISTSIM_CACHE_DIR to an empty string turns the cache off.
    """
    directory = os.environ.get("HOISTSIM_CACHE_DIR")
    if directory == "":
        return
    if directory is None:
        directory = os.path.join(os.path.expanduser("~"), ".cache", "hoistsim", "jax")
    try:
        os.makedirs(directory, exist_ok=True)
    except OSError:
        return  # a read-only home: run without the cache
    jax.config.update("jax_compilation_cache_dir", directory)
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.5)
    jax.config.update("jax_persistent_cache_min_entry_size_bytes", 0)

"""Which stored programs a command used the last time it ran, so that the next time they load while the
scenario is read.  No JAX here: the command line reads a hint before it decides to start JAX.

A hint is a small JSON file in the cache folder, named by the command (the scenario file's absolute path,
its overrides and sweeps, whether summaries only), holding the keys of the stored programs the command
was served (see :func:`hoistsim._jax.executable`).  A hint that no longer fits (the scenario's structure
changed) costs a program loaded for nothing; the right one is loaded or compiled as usual.
"""

from __future__ import annotations

import hashlib
import json
import os

from .cache_folders import cache_folder, cache_root, keep


def command_hint(scenario_path: str, *options) -> str:
    """The hint's name for a command: its scenario file and whatever else picks its programs."""
    return hashlib.sha256(repr((os.path.abspath(scenario_path), options)).encode()).hexdigest()


def _path(hint: str) -> str | None:
    if cache_root() is None:
        return None
    folder = cache_folder("hints")
    return None if folder is None else os.path.join(folder, hint + ".json")


def programs_wanted(hint: str) -> list[tuple[str, int]]:
    """(key, devices) of each stored program the command was served last time; none where it never ran,
    the cache is off or the hint cannot be read."""
    path = _path(hint)
    if path is None:
        return []
    try:
        with open(path) as handle:
            return [(str(key), int(devices)) for key, devices in json.load(handle)]
    except (OSError, ValueError, TypeError):
        return []


def remember_programs(hint: str, served: list[tuple[str, int]]) -> None:
    """Keep (atomically) the programs a command was served, for its next run; nothing where the cache is off."""
    path = _path(hint)
    if path is None:
        return
    try:
        keep(path, json.dumps(served).encode())
    except OSError:  # a full disk or a read-only cache: the next run loads its programs in turn
        pass

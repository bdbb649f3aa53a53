"""Compiled programs kept on disk between processes: written, read back, and read ahead in a thread.

A stored program is a pickle of four parts: what made it (:func:`origin`: our source's digest, JAX's and
jaxlib's versions), XLA's serialised executable, and the structures of the program's arguments and of its
results, each pickled apart as bytes.  A program of another origin is never unpickled further: the
structure of its arguments names element classes whose fields may since have changed, which XLA's tree
code would take on trust (a crash, not an error), and a program read ahead because a command ran it
before an edit or an upgrade is of another origin.  (Its key, :func:`hoistsim._jax.executable`'s, holds
the other libraries' versions too: a program of theirs is another key, never served.)  Reading the executable is XLA's
work, done with Python's lock let go (0.5 s for exercise 6's on 2 cores); unpickling the arguments'
structure imports the machine's modules (the scenario's pydantic models among them), Python's work.
Kept apart, the first runs in a thread while the command line reads the scenario
(:class:`ReadAhead`), and the second waits until the executable is read.
"""

from __future__ import annotations

import pickle
from concurrent.futures import Future, ThreadPoolExecutor

from .cache_folders import keep
from .program_origin import source_digest
from .program_pool import counting_maps


class StaleProgram(Exception):
    """A stored program made from other code or other libraries: compiled again where it is wanted."""


def origin() -> tuple:
    """What a stored program's structures are read with: our source (the element classes they name) and
    JAX's tree code (imported already where a program is stored or read; the versions' lookup by package
    metadata would cost a read ahead some 30 ms)."""
    import jax
    import jax.lib

    return source_digest(), jax.__version__, jax.lib.__version__  # jax.lib's: jaxlib's


def store(compiled, path: str) -> None:
    """Write ``compiled`` (a ``jax.stages.Compiled``) at ``path``, atomically; nothing where it cannot be."""
    from jax.experimental.serialize_executable import serialize

    try:
        executable, in_tree, out_tree = serialize(compiled)
        keep(path, pickle.dumps((origin(), executable, pickle.dumps(in_tree), pickle.dumps(out_tree))))
    except Exception:  # a full disk or an executable that cannot be serialised: still run
        pass


class _StructureOnDemand:
    """The arguments' structure, unpickled where it is first used (after XLA has read the executable)."""

    def __init__(self, pickled: bytes):
        self._pickled = pickled

    def unflatten(self, leaves):
        return pickle.loads(self._pickled).unflatten(leaves)


def read(path: str, devices: int):
    """The program stored at ``path``, loaded onto the first ``devices`` devices (raises where it cannot be)."""
    import jax
    from jax.experimental.serialize_executable import deserialize_and_load

    with open(path, "rb") as handle:
        stored = pickle.load(handle)
    if len(stored) != 4 or stored[0] != origin():
        raise StaleProgram(f"{path} was compiled from other code")
    _, executable, in_tree, out_tree = stored
    return deserialize_and_load(executable, _StructureOnDemand(in_tree), pickle.loads(out_tree),
                                execution_devices=jax.devices()[:devices])


class ReadAhead:
    """Stored programs being read in a thread, by key, until they are taken."""

    def __init__(self):
        self._reading: dict[str, Future] = {}

    def start(self, wanted: dict[str, tuple[str, int]]) -> None:
        """Read each program of ``wanted`` (key -> (path, devices)) in a thread, one after another."""
        wanted = {key: where for key, where in wanted.items() if key not in self._reading}
        if not wanted:
            return
        reader = ThreadPoolExecutor(max_workers=1, thread_name_prefix="hoistsim-read-ahead")
        for key, (path, devices) in wanted.items():
            self._reading[key] = reader.submit(self._read, path, devices)
        reader.shutdown(wait=False)

    @staticmethod
    def _read(path: str, devices: int):
        try:
            return counting_maps(lambda: read(path, devices))
        except Exception:  # absent, stale or unreadable: loaded or compiled in turn where it is wanted
            return None, None

    def take(self, key: str):
        """(the program read ahead under ``key``, the memory maps it took), waiting for it; (None, None)
        where none was read ahead or it could not be read."""
        reading = self._reading.pop(key, None)
        return (None, None) if reading is None else reading.result()

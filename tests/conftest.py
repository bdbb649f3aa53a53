"""The session's set-up: caches kept out of the user's home, two CPU devices, one JAX compilation cache for
every process, float64 JAX (hoistsim turns it on at import).  What the tests share in code is in helpers.py."""

from __future__ import annotations

import gc
import os
import sys
from pathlib import Path

import pytest

# The on-disk caches serve fresh `hoistsim` processes; in the test session, commands
# run in-process and share jit's in-memory cache instead, and nothing is written to
# the user's home.  Tests of the caches give their subprocesses a folder of their own.
os.environ["HOISTSIM_CACHE_DIR"] = ""
# Two CPU devices in every test process whatever the machine's cores: a sweep's chunks are split over
# them (hoistsim.running.blocks) everywhere the suite runs, and its numbers are the same bits on every machine.
os.environ["HOISTSIM_CPU_DEVICES"] = "2"

# One JAX compilation cache for the whole session, in a fresh folder: a program one process compiled
# (either xdist worker, a Dask worker, a command run in a subprocess) is loaded by the others, and again
# after _compiled_programs_within_the_map_limit lets a process's programs go.  The first process to
# import this file makes the folder; those it starts inherit it and leave it be.
if "JAX_COMPILATION_CACHE_DIR" not in os.environ:
    import atexit
    import shutil
    import tempfile

    _session_cache = tempfile.mkdtemp(prefix="hoistsim-tests-jax-")
    os.environ["JAX_COMPILATION_CACHE_DIR"] = _session_cache
    os.environ["JAX_PERSISTENT_CACHE_MIN_COMPILE_TIME_SECS"] = "0.5"
    atexit.register(shutil.rmtree, _session_cache, ignore_errors=True)

import hoistsim._jax  # noqa: E402,F401  (float64 before any test creates an array)

sys.path.insert(0, str(Path(__file__).parent))  # `from helpers import ...` from every folder of the tests


def _memory_maps() -> tuple[int, int]:
    """(memory maps this process holds, the most the kernel allows it); (0, 1) where /proc cannot tell."""
    try:
        with open("/proc/self/maps") as maps, open("/proc/sys/vm/max_map_count") as limit:
            return sum(1 for _ in maps), int(limit.read())
    except OSError:
        return 0, 1


@pytest.fixture(autouse=True, scope="module")
def _compiled_programs_within_the_map_limit():
    """Each compiled XLA program holds some 600 memory maps, and a process past the kernel's limit
    (vm.max_map_count, 65 530 by default) aborts in its next compile.  The suite compiles well over a
    hundred programs in one process: after a test module, once 70 % of the limit is used (a module
    compiles at most a few dozen), the compiled programs are let go (the modules after it compile what
    they need again)."""
    yield
    held, limit = _memory_maps()
    if held > 0.7 * limit:
        _let_compiled_programs_go()


# What one test process may hold before it lets its compiled programs go: the machine's memory (24 GB on
# CI's 2 cores) is shared by the two test processes and what they compile (the drawing guide's
# every-part drivetrain peaks at some 7 GB while XLA compiles it); a process that kept every program of the modules it
# ran grew past 10 GB, and two of them and a compile ran the machine out of memory.
RESIDENT_BUDGET = 5e9  # bytes


def _resident() -> float:
    """This process's resident memory, bytes (0 where /proc cannot tell)."""
    try:
        with open("/proc/self/statm") as statm:
            return int(statm.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")
    except (OSError, ValueError):
        return 0.0


@pytest.fixture(autouse=True)
def _compiled_programs_within_the_memory_budget():
    """After a test, a process over :data:`RESIDENT_BUDGET` lets its compiled programs go (the tests after it
    load what they need again from the session's compilation cache, a fraction of a compile)."""
    yield
    if _resident() > RESIDENT_BUDGET:
        _let_compiled_programs_go()


def _let_compiled_programs_go() -> None:
    import ctypes

    import jax

    from hoistsim import _jax

    _jax.programs.clear()
    jax.clear_caches()
    gc.collect()
    try:  # hand the freed heap back to the system, so that the next test's budget reads true
        ctypes.CDLL("libc.so.6").malloc_trim(0)
    except (OSError, AttributeError):
        pass

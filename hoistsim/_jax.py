"""JAX set-up: float64 before any array exists, a CPU device per core, and a persistent compilation cache.

Imported first by the package, so that every array hoistsim creates is float64.
"""

from __future__ import annotations

import contextlib
import hashlib
import os

import jax

from .cache_folders import cache_folder, cache_root
from .program_origin import program_origin
from .program_origin import source_digest as source_digest  # the digest stored programs are keyed by
from .program_pool import ProgramPool
from .stored_programs import ReadAhead, read, store

jax.config.update("jax_enable_x64", True)

# Name of the variable that sets how many CPU devices XLA makes (default: one per core this process may use).
CPU_DEVICES_VARIABLE = "HOISTSIM_CPU_DEVICES"


def cpu_devices_wanted() -> int:
    """CPU devices to ask XLA for: HOISTSIM_CPU_DEVICES, else one per core this process may use.

    XLA runs a program on one device at a time and a vectorised loop of small
    operations gains next to nothing from its threads within a device: measured
    on 2 cores, a sweep's chunk split over two devices (each running its half)
    costs 12 us a run where one device takes 20.  :mod:`hoistsim.running.blocks` splits
    every chunk over the devices there are.
    """
    value = os.environ.get(CPU_DEVICES_VARIABLE, "").strip()
    if value.isdigit() and int(value) > 0:
        return int(value)
    return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count() or 1


def _ask_for_cpu_devices() -> None:
    """Set the CPU device count, unless the user set it (XLA_FLAGS or jax's config) or JAX already started:
    then the devices are as they are."""
    if "xla_force_host_platform_device_count" in os.environ.get("XLA_FLAGS", "") \
            or jax.config.jax_num_cpu_devices != -1:
        return
    try:
        jax.config.update("jax_num_cpu_devices", cpu_devices_wanted())
    except RuntimeError:  # a backend already initialised (jax used before hoistsim was imported)
        pass


_ask_for_cpu_devices()


def _cpu_program_built_on_every_core() -> None:
    """Have XLA build a CPU program as one LLVM module per core, compiled side by side, unless the user chose.

    A run's program is some hundreds of small kernels; split over the cores,
    LLVM builds them in parallel.  Measured on 2 cores, fresh processes
    alternating (``.lower().compile()``): exercise 6 3.8, 4.1 s as one module,
    3.0, 3.3 s as two; CoupledClutches 15.0, 11.2 s as one, 12.1, 9.2 s as two.
    Such a program, serialised, keeps every module's kernels, except where JAX's
    own persistent cache served the compile: see :func:`_own_compile`.  (An
    earlier jaxlib lost kernels either way; a program that fails to load or to
    run is compiled afresh, see :func:`_falling_back`.)
    Read when the backend starts, so it counts only if hoistsim is imported
    before JAX computes anything.
    """
    _default_xla_flag("xla_cpu_parallel_codegen_split_count", str(cpu_devices_wanted()))


def _legacy_cpu_fusion_emitters() -> None:
    """Have XLA emit each fused kernel of a CPU program with its older LLVM emitters, unless the user chose.

    A run's program is a loop of some hundreds of small scalar fusions; XLA's
    newer (MLIR) fusion emitters take a fifth more time to build them, and the
    code they make runs no faster here.  Measured on 2 cores, fresh processes
    alternating: exercise 6 compiles in 6.1 s instead of 8.0, every friction
    element in 15.5 s instead of 19.9 (XLA's part), a sweep's run costs 30 us
    instead of 35, and the stored program is 8 % smaller (it loads sooner);
    the lock-up instants agree to the last digit.
    """
    _default_xla_flag("xla_cpu_use_fusion_emitters", "false")


def _default_xla_flag(name: str, value: str) -> None:
    flags = os.environ.get("XLA_FLAGS", "")
    if name not in flags:
        os.environ["XLA_FLAGS"] = (flags + f" --{name}={value}").strip()


_cpu_program_built_on_every_core()
_legacy_cpu_fusion_emitters()


_executables: str | None = None  # folder of serialised executables, when the cache is on
programs = ProgramPool()  # the programs this process has compiled or loaded, by key
# Set by the command line: a context manager, given the program's name, that tells the user a
# compilation is under way (it takes seconds, and the first run of a scene would otherwise sit silent).
compile_notice = None
read_ahead = ReadAhead()  # stored programs being read while the host works (see preload)
_served: list | None = None  # (key, devices) of each program served while serving_recorded() runs


def enable_compilation_cache() -> None:
    """Keep compiled solvers on disk, so a second `hoistsim run` skips compilation.

    XLA keeps no program with host callbacks in the cache, and equinox's runtime
    checks are host callbacks unless EQX_ON_ERROR=nan, which the command line
    sets before equinox is imported (hoistsim checks each run's status itself).

    The directory is HOISTSIM_CACHE_DIR, else ~/.cache/hoistsim/jax; setting
    HOISTSIM_CACHE_DIR to an empty string turns the cache off.
    """
    executables = cache_folder("executables")
    if executables is None:
        return
    global _executables
    _executables = executables
    jax.config.update("jax_compilation_cache_dir", cache_root())
    jax.config.update("jax_persistent_cache_min_compile_time_secs", 0.5)
    jax.config.update("jax_persistent_cache_min_entry_size_bytes", 0)


def stores_programs() -> bool:
    """Whether compiled programs are kept on disk for later processes (the cache is on)."""
    return _executables is not None


def structure_of(*args) -> str:
    """What a compiled program depends on of its arguments: their tree, shapes and dtypes (not their values)."""
    leaves, treedef = jax.tree.flatten(args)
    return repr((str(treedef), [(getattr(x, "shape", ()), str(getattr(x, "dtype", type(x)))) for x in leaves]))


def executable(program, *args, name: str, devices: int = 1):
    """``program()`` (a jitted function) compiled for ``args``: held by the process's pool of programs, or
    loaded from disk when a run of the same shape compiled it before, or compiled.

    ``program`` is called only where neither can serve: a loaded run never
    imports or traces the loop.  Every program is compiled ahead of time and
    held by :data:`programs` alone (never by jit's own caches), so that the
    least recently used can be let go before the process runs out of memory
    maps (:mod:`.program_pool`).

    ``devices``: how many of the process's devices the program runs on (the
    first ones); a loaded program is bound to them, not to every device the
    backend has, which a program built for fewer could not run on.

    JAX's persistent cache saves the compilation but not the tracing of the
    Python loop (~0.5 s), which has to happen to find the cache key; a
    serialised executable skips both.  The key covers everything the program
    depends on: the package's source (:func:`source_digest`), the versions of
    the libraries that trace it, the backend, XLA's flags (a program built with
    other flags is another program), the function's name and the arguments'
    structure, shapes and dtypes.
    """
    signature = repr((name, program_origin(), jax.default_backend(), os.environ.get("XLA_FLAGS", ""), devices,
                      structure_of(*args)))
    key = hashlib.sha256(signature.encode()).hexdigest()
    if _served is not None and (key, devices) not in _served:
        _served.append((key, devices))
    held = programs.get(key)
    if held is not None:
        return held
    ahead, maps = read_ahead.take(key)
    if ahead is not None:
        return programs.make(key, lambda: _falling_back(ahead, program, args, key, _stored_at(key)), maps=maps)
    return programs.make(key, lambda: _load_or_compile(program, args, name, key, devices))


def _stored_at(key: str) -> str:
    return os.path.join(_executables, key + ".bin")


def _load_or_compile(program, args, name: str, key: str, devices: int):
    if _executables is not None:
        path = _stored_at(key)
        try:
            return _falling_back(read(path, devices), program, args, key, path)
        except Exception:  # absent, stale or unreadable: compile afresh
            pass
    with compile_notice(name) if compile_notice is not None else contextlib.nullcontext(), _own_compile():
        compiled = program().lower(*args).compile()
    if _executables is not None:
        store(compiled, _stored_at(key))
    return compiled


@contextlib.contextmanager
def _own_compile():
    """Within: XLA compiles, JAX's persistent cache neither serves nor keeps the program, where hoistsim
    stores it itself.

    A CPU program JAX's cache serves is read back from that cache; built as one
    module per core (:func:`_cpu_program_built_on_every_core`) and serialised
    again, it lacks some of its kernels, and the next process fails to run it
    ("Function div.130_kernel not found"): stored, read, failed and compiled
    again at every other run.
    """
    if _executables is None:
        yield
        return
    was = jax.config.jax_enable_compilation_cache
    jax.config.update("jax_enable_compilation_cache", False)
    try:
        yield
    finally:
        jax.config.update("jax_enable_compilation_cache", was)


def preload(wanted) -> None:
    """Start reading stored programs, (key, devices) each, in a thread (see :mod:`.stored_programs`):
    the command line has them read while it reads the scenario that asks for them, and
    :func:`executable` takes one from there when its key comes up."""
    if _executables is not None and wanted:
        # the source's digest, which the reading checks each program's origin against, worked out here: in the
        # reading thread its 150 file reads would each hand Python's lock to this thread's imports
        source_digest()
        read_ahead.start({key: (_stored_at(key), devices) for key, devices in wanted if key not in programs})


@contextlib.contextmanager
def serving_recorded():
    """Within: the (key, devices) of every program served, in order, in the list this yields."""
    global _served
    _served = served = []
    try:
        yield served
    finally:
        _served = None


def _falling_back(loaded, program, args, key: str, path: str):
    """Call a loaded executable; if XLA cannot run it in this process, forget it and compile ``program()``.

    (A stored program that loads and then fails at its first call was seen once,
    and an older jaxlib wrote such programs: see
    :func:`_cpu_program_built_on_every_core`; the answer is then computed the
    usual way.)  The first call is waited for, where such a failure shows;
    later ones return at once, so that a sweep's host work goes on while they
    run.
    """
    ran = []

    def call(*call_args):
        if ran:
            return loaded(*call_args)
        try:
            out = jax.block_until_ready(loaded(*call_args))  # errors surface here, not at the call
            ran.append(True)
            return out
        except Exception:
            try:
                os.unlink(path)
            except OSError:
                pass
            compiled = program().lower(*args).compile()
            programs.replace(key, compiled)
            return compiled(*call_args)

    return call

"""The compiled programs a process holds, the least recently used let go before the kernel's limit.

Each compiled XLA CPU program holds memory maps (700 to 1300 for a scene's
loop, measured), and a process past the kernel's limit (vm.max_map_count,
65 530 by default: some fifty scenes) aborts inside XLA at its next compile.
A long-lived process (``hoistsim watch``, a Dask worker, a notebook) may meet
many structures: the pool counts the maps each program took when it was made
and, before another is made, lets the least recently used go until the
process is back under a share of the limit.  A program let go is compiled (or
loaded from disk) again if it is wanted again.  Where /proc cannot tell, the
pool keeps at most ``HOISTSIM_MAX_PROGRAMS`` (default 32).  No JAX here.
"""

from __future__ import annotations

import gc
import os
from collections import OrderedDict

MAX_PROGRAMS_VARIABLE = "HOISTSIM_MAX_PROGRAMS"
MAP_SHARE = 0.6  # of vm.max_map_count: room left for the compile under way and for what else the process maps
DEFAULT_MAX_PROGRAMS = 32


def memory_maps() -> tuple[int, int] | None:
    """(memory maps this process holds, the most the kernel allows it), or None where /proc cannot tell."""
    try:
        with open("/proc/self/maps") as maps, open("/proc/sys/vm/max_map_count") as limit:
            return sum(1 for _ in maps), int(limit.read())
    except (OSError, ValueError):
        return None


def max_programs() -> int | None:
    value = os.environ.get(MAX_PROGRAMS_VARIABLE, "").strip()
    if value.isdigit() and int(value) > 0:
        return int(value)
    return None if memory_maps() is not None else DEFAULT_MAX_PROGRAMS


def counting_maps(build):
    """(``build()``, the memory maps the process gained while it ran: 0 where /proc cannot tell)."""
    before = memory_maps()
    made = build()
    after = memory_maps()
    return made, max(0, after[0] - before[0]) if before and after else 0


class ProgramPool:
    """Compiled programs by key, least recently used first."""

    def __init__(self):
        self._held: OrderedDict[str, tuple[object, int]] = OrderedDict()  # key -> (program, maps it took)
        self.let_go = 0  # programs let go so far (for tests and benchmarks)

    def __contains__(self, key: str) -> bool:
        return key in self._held

    def __len__(self) -> int:
        return len(self._held)

    def get(self, key: str):
        """The program, now the most recently used; None if not held."""
        if key not in self._held:
            return None
        self._held.move_to_end(key)
        return self._held[key][0]

    def make(self, key: str, build, maps: int | None = None):
        """``build()``'s program, held under ``key``, after making room for it; ``maps``: the memory maps it
        took where it was made elsewhere (a program loaded beforehand), else counted around ``build``."""
        self.make_room()
        program, counted = counting_maps(build)
        self._held[key] = (program, counted if maps is None else maps)
        return program

    def replace(self, key: str, program) -> None:
        """Hold ``program`` under ``key`` instead (a loaded program that fell back to compiling)."""
        maps = self._held[key][1] if key in self._held else 0
        self._held[key] = (program, maps)
        self._held.move_to_end(key)

    def make_room(self) -> None:
        """Let the least recently used programs go: at most one fewer than the count allowed, and (on Linux)
        until the process holds less than MAP_SHARE of its maps limit with room for the largest program yet."""
        most = max_programs()
        while self._held and most is not None and len(self._held) >= most:
            self._let_go_oldest()
        while self._held:
            maps = memory_maps()
            if maps is None:
                return
            largest = max(m for _, m in self._held.values())
            if maps[0] + largest < MAP_SHARE * maps[1]:
                return
            self._let_go_oldest()

    def _let_go_oldest(self) -> None:
        self._held.popitem(last=False)
        self.let_go += 1
        gc.collect()  # XLA unmaps a program when its last reference goes: count what is left, not what was

    def clear(self) -> None:
        self._held.clear()
        gc.collect()

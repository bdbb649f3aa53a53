"""What the command line says on a terminal while it works (a compilation under way, a sweep's progress), and how
wide its tables may be.

The first two write to stderr, so stdout keeps only the tables a user may pipe.
"""

from __future__ import annotations

import contextlib
import shutil
import sys
import threading
import time

import click


# A table's width where stdout is not a terminal (a pipe, a file) and COLUMNS is not set.
PIPED_WIDTH = 100


def table_width(wide: bool = False) -> int | None:
    """How wide a table may print: COLUMNS where set, else the terminal's width, else PIPED_WIDTH; None with
    ``wide`` (the whole table, however wide)."""
    if wide:
        return None
    return max(shutil.get_terminal_size((PIPED_WIDTH, 24)).columns, 40)


@contextlib.contextmanager
def compiling(name: str):
    """Say on stderr that a scene's solver is compiling: one line, and on a terminal the seconds as they pass."""
    from .. import _jax

    text = ("hoistsim: compiling the solver for this scene's structure "
            + ("(once; later runs load it)" if _jax.stores_programs()
               else "(the compiled-solver cache is off: each process compiles)"))
    if not sys.stderr.isatty():
        click.echo(text, err=True)
        yield
        return
    started = time.perf_counter()
    done = threading.Event()

    def tick() -> None:
        while not done.wait(0.25):
            click.echo(f"\r{text}: {time.perf_counter() - started:.0f} s", err=True, nl=False)

    ticker = threading.Thread(target=tick, daemon=True)
    ticker.start()
    try:
        yield
    finally:
        done.set()
        ticker.join()
        click.echo(f"\r{text}: done in {time.perf_counter() - started:.1f} s", err=True)


def progress_printer():
    """Progress of a long sweep on stderr, only when stderr is a terminal."""
    if not sys.stderr.isatty():
        return None
    started = time.perf_counter()

    def show(done: int, total: int) -> None:
        elapsed = time.perf_counter() - started
        left = elapsed / done * (total - done) if done else 0.0
        end = "\n" if done == total else ""
        click.echo(f"\r  {done}/{total} runs ({100 * done / total:.0f} %), {elapsed:.1f} s, ~{left:.0f} s left   ",
                   err=True, nl=False)
        if end:
            click.echo("", err=True)

    return show

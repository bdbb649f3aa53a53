"""Figures of a results file: the runs against time, the summary against the swept value, the periodic regime.

The panels come from the parts' displays (:mod:`hoistsim.display`): each part the
file's runs have columns of draws its own, so this module names no part.
matplotlib is imported here and in the other figure modules only, so the rest
of hoistsim never pays for it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..display import DISPLAYS
from ..display.part_names import part_names_of
from ..results.atomic import atomic_path
from ..results.part_names import names_table
from ..results.reading import read_runs, read_summary, read_swept_keys
from .base import DISPLAY_UNITS


def plot_file(path, output, *, frames=None, png_compression: int = 6) -> list[str]:
    """Write the figures of a results file; returns the paths written.

    OUT.png: the runs against time; OUT_summary.png: the summary against the
    swept value (a sweep, or a summary-only file, then OUT.png itself);
    OUT_periodic.png: the first run's periodic regime.  ``frames``: where the
    runs' figure gets its frame (:class:`.frames.KeptFrames` keeps it for the
    next call); ``png_compression``: zlib's level, 0-9 (1 writes a figure in
    two thirds of the time of 6, 15 % larger).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .frames import DPI, FreshFrames

    frames = frames or FreshFrames()
    output = Path(output)
    written = []
    for suffix, fig in draw_figures(path, plt, frames):
        target = output.with_name(output.stem + suffix + output.suffix)
        with atomic_path(target) as partial:  # a figure open in a viewer is replaced whole, never half-drawn
            form = target.suffix[1:].lower()
            fig.savefig(partial, dpi=DPI, format=form,
                        **({"pil_kwargs": {"compress_level": png_compression}} if form == "png" else {}))
        frames.done(plt, fig)
        written.append(str(target))
    return written


def draw_figures(path, plt, frames):
    """The figures of a results file, each as it is drawn: (what its file's name adds to OUT's stem, the figure).

    The caller lets each go (``frames.done``) before it takes the next.
    """
    from .runs import runs_figure
    from .summary import summary_figure

    summaries = read_summary(path)
    swept = swept_axis(path, summaries)
    parameters = scenario_parameters(path)
    runs = read_runs(path, columns=runs_columns(names_table(parameters)),
                     attributes=("label", "name", *read_swept_keys(path)))
    if runs:
        yield "", runs_figure(runs, plt, swept, frames)
    periodic = [run for run in runs if "turning_moment" in run]
    if periodic:  # the first run's periodic regime: its turning-moment diagram and speed over a period
        from .periodic import periodic_figure

        yield "_periodic", periodic_figure(periodic[0], plt)
    if len(summaries) > 1 or not runs:
        yield "_summary" if runs else "", summary_figure(summaries, swept, plt, scenario_name(path), parameters)


def draw_runs_figure(runs, output, *, frames=None, png_compression: int = 6) -> "FigureWriting":
    """The figure of ``runs`` (dicts as :func:`.reading.read_runs` gives, one run or a few) drawn now, and
    written to ``output`` (PNG) by a thread: :meth:`FigureWriting.join` it before the next figure.

    What ``hoistsim watch`` uses to draw a run while its results file is written: the PNG's compression,
    a tenth of the figure's time, runs beside the file's writing (zlib lets go of Python's lock).  The
    file is the one :func:`plot_file` writes (same pixels, same metadata; tests/cli/test_watch.py).
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image
    import matplotlib.pyplot as plt

    from .frames import FreshFrames
    from .runs import runs_figure

    frames = frames or FreshFrames()
    fig = runs_figure(runs, plt, ("run", np.arange(len(runs), dtype=float), ""), frames)
    fig.canvas.draw()
    pixels = fig.canvas.buffer_rgba()
    target = Path(output)

    def write():
        with atomic_path(target) as partial:
            matplotlib.image.imsave(partial, pixels, format="png", origin="upper", dpi=fig.dpi,
                                    pil_kwargs={"compress_level": png_compression})

    return FigureWriting(write, lambda: frames.done(plt, fig))


class FigureWriting:
    """A drawn figure's file being written by a thread; :meth:`join` waits for it, then lets the figure go
    (on the caller's thread: pyplot is not for two threads) and raises what the writing raised."""

    def __init__(self, write, done):
        import threading

        self._done, self._failed = done, None

        def run():
            try:
                write()
            except BaseException as exc:  # handed to join: a thread's own exception would go to stderr alone
                self._failed = exc

        self._thread = threading.Thread(target=run, name="hoistsim-figure")
        self._thread.start()

    def join(self) -> None:
        self._thread.join()
        self._done()
        if self._failed is not None:
            raise self._failed


class _Read:
    """The columns the run figure reads: those the parts' panels, marks and shading name, and those a
    part named by the user claims (``reads``: under its part's name, a hoist's ``slip_speed`` the clutch's
    ``clutch_slip``); the rest of a file is not loaded."""

    def __init__(self, names: dict):
        self.part_names = part_names_of(names)
        self.names = {"time", "motor_angle"}
        for display in DISPLAYS:
            for panel in display.panels:
                for trace in panel.traces:
                    self.names.update(trace.columns())
            self.names.update(phase.column for phase in display.shading)

    def __contains__(self, name: str) -> bool:
        name_read = self.part_names.get(name, name)
        return name in self.names or any(display.reads_column(name_read) for display in DISPLAYS)


def runs_columns(names: dict | None = None) -> _Read:
    """The columns the run figure reads of a run whose names table is ``names`` (:mod:`hoistsim.display.part_names`;
    none: a drawn drivetrain's)."""
    return _Read(names or {})


def scenario_parameters(path) -> dict:
    """The scenario in SI numbers as the file keeps it (the resolved base of a sweep), {} where it has none."""
    import json

    import h5py

    with h5py.File(path, "r") as f:
        text = f["runs"].attrs.get("parameters") if "runs" in f else None
    return json.loads(text) if text else {}


def scenario_name(path) -> str:
    """The scenario's ``name:`` as the file keeps it (its text under /scenario)."""
    import re

    import h5py

    with h5py.File(path, "r") as f:
        text = f["scenario"][()] if "scenario" in f else b""
    text = text.decode() if isinstance(text, bytes) else str(text)
    found = re.search(r"^name:[ \t]*['\"]?([^'\"\n#]*)", text, re.MULTILINE)
    return found.group(1).strip() if found else ""


def swept_axis(path, summaries):
    """(name, values in display units, unit) of the first swept key with numbers, else the run index."""
    for key in read_swept_keys(path):
        values = np.asarray([row[key] for row in summaries], dtype=float)
        if np.all(np.isfinite(values)):
            scale, unit = DISPLAY_UNITS.get(key.rsplit(".", 1)[-1], (1.0, "SI"))
            return key, values * scale, unit
    return "run", np.arange(len(summaries), dtype=float), ""

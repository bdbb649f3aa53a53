"""Figures of a results file: the runs against time, the summary against the swept value, the periodic regime.

The panels come from the elements (:mod:`hoistsim.core.panel`): each part the
file's runs have columns of draws its own, so this module names no part.
matplotlib is imported here and in the ``plotting_*`` modules only, so the rest
of hoistsim never pays for it.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .atomic import atomic_path
from .core.panel import RPM
from .elements import element_classes as element_classes  # noqa: F401  (the figures' modules read it here)
from .reading import read_runs, read_summary, read_swept_keys


def plot_file(path, output) -> list[str]:
    """Write the figures of a results file; returns the paths written.

    OUT.png: the runs against time; OUT_summary.png: the summary against the
    swept value (a sweep, or a summary-only file, then OUT.png itself);
    OUT_periodic.png: the first run's periodic regime.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .plotting_runs import runs_figure
    from .plotting_summary import summary_figure

    output = Path(output)
    summaries = read_summary(path)
    swept = swept_axis(path, summaries)
    runs = read_runs(path, columns=runs_columns(), attributes=("label", "name", *read_swept_keys(path)))
    written = []

    def save(fig, target):
        with atomic_path(target) as partial:  # a figure open in a viewer is replaced whole, never half-drawn
            fig.savefig(partial, dpi=150, format=target.suffix[1:].lower())
        plt.close(fig)
        written.append(str(target))

    if runs:
        save(runs_figure(runs, plt, swept), output)
    periodic = [run for run in runs if "turning_moment" in run]
    if periodic:  # the first run's periodic regime: its turning-moment diagram and speed over a period
        from .plotting_periodic import periodic_figure

        save(periodic_figure(periodic[0], plt), output.with_name(output.stem + "_periodic" + output.suffix))
    if len(summaries) > 1 or not runs:
        target = output.with_name(output.stem + "_summary" + output.suffix) if runs else output
        save(summary_figure(summaries, swept, plt, scenario_name(path), scenario_parameters(path)), target)
    return written


class _Read:
    """The columns the run figure reads: those the elements' panels, marks and shading name, and those a
    part named by the user claims (``reads``); the rest of a file is not loaded."""

    def __init__(self):
        self.classes = element_classes()
        self.names = {"time", "motor_angle"}
        for cls in self.classes:
            for panel in cls.panels:
                for trace in panel.traces:
                    self.names.update(trace.columns())
            self.names.update(phase.column for phase in cls.shading)

    def __contains__(self, name: str) -> bool:
        return name in self.names or any(cls.reads(name) for cls in self.classes)


def runs_columns() -> _Read:
    return _Read()


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
    from .reading import read_swept_keys

    for key in read_swept_keys(path):
        values = np.asarray([row[key] for row in summaries], dtype=float)
        if np.all(np.isfinite(values)):
            scale, unit = _DISPLAY_UNITS.get(key.rsplit(".", 1)[-1], (1.0, "SI"))
            return key, values * scale, unit
    return "run", np.arange(len(summaries), dtype=float), ""


# how a swept key is shown: SI value x scale, in unit
_DISPLAY_UNITS = {
    "engagement_force": (1.0, "N"), "mass": (1.0, "kg"), "release_time": (1.0, "s"),
    "motor_speed": (RPM, "rpm"), "drum_speed": (RPM, "rpm"), "no_load_speed": (RPM, "rpm"),
    "stall_torque": (1.0, "N*m"), "static_friction": (1.0, "-"), "kinetic_friction": (1.0, "-"),
    "half_angle": (180.0 / math.pi, "deg"), "duration": (1.0, "s"), "inertia": (1.0, "kg*m^2"),
}


def swept_label(swept) -> str:
    key, _, unit = swept
    return f"{key} [{unit}]" if unit and unit != "SI" else key


def colour_scale(values, plt):
    """A colour for each run by its swept value (viridis, its bright end left out for contrast on white)."""
    values = np.asarray(values, dtype=float)
    low, high = float(values.min()), float(values.max())
    if high <= low:
        low, high = low - 1.0, high + 1.0
    from matplotlib.colors import ListedColormap

    norm = plt.Normalize(low, high)
    cmap = ListedColormap(plt.get_cmap("viridis")(np.linspace(0.0, 0.9, 256)))
    return cmap(norm(values)), cmap, norm

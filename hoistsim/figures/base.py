"""What the figures share: a swept key's display units and label, a run's colour by its swept value, an event
row's text."""

from __future__ import annotations

import math

import numpy as np

from ..display.panel import RPM

# how a swept key is shown: SI value x scale, in unit
DISPLAY_UNITS = {
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


def row_text(row, name: str) -> str:
    """A text field of an event row (its kind, element, category), "" where the file has none."""
    value = row[name] if name in (row.dtype.names or ()) else ""
    return value.decode() if isinstance(value, bytes) else str(value)

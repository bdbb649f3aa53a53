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


def flat_where_round_off(ax, drawn) -> None:
    """A panel of a quantity constant to round-off (a steady lift's speed, a locked clutch's slip, a rollback of
    nothing) is drawn flat, not as 1e-14 wiggles on an offset scale: a range below a millionth of the values,
    or values all below 1e-9 in the panel's units, is round-off.  ``drawn``: the arrays of its curves."""
    values = np.concatenate([np.asarray(v, dtype=float).ravel() for v in drawn]) if drawn else np.zeros(1)
    values = values[np.isfinite(values)]
    if values.size == 0:
        return
    low, high = float(values.min()), float(values.max())
    centre = 0.5 * (low + high)
    if max(abs(low), abs(high)) < 1e-9:
        ax.set_ylim(-1.0, 1.0)
    elif high - low < 1e-6 * max(abs(low), abs(high)):
        pad = 0.05 * abs(centre)
        ax.set_ylim(centre - pad, centre + pad)
    ax.ticklabel_format(axis="y", useOffset=False)

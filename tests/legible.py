"""What every figure must be, whatever it draws: its events' names apart and off the curves, under the title,
and every marker whole inside its panel.  Read from the drawn figure (its texts' and markers' boxes on the
canvas), so a figure that breaks it fails whichever code placed them.
"""

from __future__ import annotations

import numpy as np
from matplotlib.collections import PathCollection

from hoistsim.figures.naming import FONT


def panels(fig):
    return [ax for ax in fig.axes if ax.get_visible() and ax.get_label() != "<colorbar>"
            and ax.get_position().width > 0 and not _secondary(ax)]


def _secondary(ax) -> bool:
    return any(ax in other.child_axes for other in ax.figure.axes)


def legible(fig) -> None:
    """Both checks on one drawing of ``fig`` (a figure of seven panels takes most of a second to draw)."""
    fig.canvas.draw()
    event_names_apart(fig, drawn=True)
    markers_inside(fig, drawn=True)


def event_names_apart(fig, drawn=False) -> list[str]:
    """No two event names on each other nor touching (a name's width apart at least), each above its panel,
    between the panel's sides and under the title: off every curve.  Returns their texts."""
    if not drawn:
        fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    pixels = fig.dpi / 72.0
    title = fig._suptitle.get_window_extent(renderer) if fig._suptitle is not None else None
    names, boxes = [], []
    for ax in panels(fig):
        frame = ax.get_window_extent(renderer)
        for text in ax.texts:
            if text.get_gid() != "event name":
                continue
            box = text.get_window_extent(renderer)
            assert box.y0 >= frame.y1 - 0.5, f"{text.get_text()!r} runs into its panel's curves"
            assert frame.x0 - 1 <= box.x0 and box.x1 <= frame.x1 + 1, f"{text.get_text()!r} past its panel's side"
            if title is not None:
                assert box.y1 <= title.y0 + 0.5, f"{text.get_text()!r} runs into the title"
            names.append(text.get_text())
            boxes.append(box)
    for i, a in enumerate(boxes):
        for j in range(i + 1, len(boxes)):
            b = boxes[j]
            if a.y1 > b.y0 and b.y1 > a.y0:  # side by side: a name's width between them
                gap = max(b.x0 - a.x1, a.x0 - b.x1)
                assert gap >= FONT * pixels - 0.5, (names[i], names[j], gap / pixels)
    return names


def markers_inside(fig, drawn=False) -> int:
    """Every marker (a dot on a curve, a run's point) whole inside its panel, none cut by the panel's edge nor
    drawn past it; returns how many were checked."""
    if not drawn:
        fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    pixels = fig.dpi / 72.0
    checked = 0
    for ax in panels(fig):
        frame = ax.get_window_extent(renderer)
        for centres, radius, clipped, what in _markers(ax, pixels):
            for x, y in centres:
                if not (np.isfinite(x) and np.isfinite(y)):
                    continue
                inside = (frame.x0 - 0.5 <= x - radius and x + radius <= frame.x1 + 0.5
                          and frame.y0 - 0.5 <= y - radius and y + radius <= frame.y1 + 0.5)
                away = (x + radius <= frame.x0 or x - radius >= frame.x1
                        or y + radius <= frame.y0 or y - radius >= frame.y1)
                assert inside or (clipped and away), (
                    f"{what} at ({x:.1f}, {y:.1f}) px, {radius:.1f} px across half, against the edges of "
                    f"{ax.get_ylabel()!r} ({frame.x0:.1f}..{frame.x1:.1f}, {frame.y0:.1f}..{frame.y1:.1f})")
                checked += 1
    return checked


def _markers(ax, pixels):
    """(centres in pixels, half a marker's width in pixels, whether the panel clips it, its name) of each
    line's markers and each scatter of ``ax``."""
    for line in ax.get_lines():
        if not line.get_visible() or line.get_marker() in (None, "None", "", " ") or len(line.get_xdata()) == 0:
            continue
        radius = 0.5 * (line.get_markersize() + line.get_markeredgewidth()) * pixels
        xy = np.column_stack([np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)])
        yield line.get_transform().transform(xy), radius, line.get_clip_on(), line.get_label() or "a marker"
    for collection in ax.collections:
        if not isinstance(collection, PathCollection) or not collection.get_visible():
            continue
        offsets = np.asarray(collection.get_offsets(), float)
        if offsets.size == 0:
            continue
        sizes = collection.get_sizes()
        widths = collection.get_linewidths()
        radius = 0.5 * (np.sqrt(float(np.max(sizes))) + float(np.max(widths) if len(widths) else 0.0)) * pixels
        yield (collection.get_offset_transform().transform(offsets), radius, collection.get_clip_on(),
               collection.get_label() or "a dot")

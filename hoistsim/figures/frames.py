"""A figure's frame: its panels, their ticks and right-hand scales, kept between runs by ``hoistsim watch``.

Making a figure of six panels builds some hundred tick objects (each two
lines and two texts) and a secondary axis per right-hand scale before a curve
is drawn: about a third of the time from a save to its figure.  A run of the
same scene needs the same frame, so :class:`KeptFrames` keeps the last one and
hands it back emptied of what a run drew on it (its curves, shading, events,
legends), which matplotlib supports artist by artist (``Artist.remove``).
The figure comes out the same, pixel for pixel, as one drawn afresh
(tests/figures/test_figures.py).
"""

from __future__ import annotations

from dataclasses import dataclass


# A figure's dots per inch, as saved.  Made at this resolution, the figure is laid out (its texts measured)
# by the renderer that then draws it, and each text's size is measured once, not again at another scale.
DPI = 150


@dataclass(frozen=True)
class FrameSpec:
    """What fixes a frame: the panels' height ratios, the figure's size, its layout, each panel's
    right-hand scale (its label, or None), and whether a column of panels enlarges a burst of events
    (:mod:`.zoom`)."""

    heights: tuple[float, ...]
    figsize: tuple[float, float]
    layout: str | None
    right: tuple[str | None, ...]
    zoom: bool = False


class RightScale:
    """A panel's right-hand scale: the panel's values times ``factor`` (set by each run, read at each draw)."""

    def __init__(self, factor: float = 1.0):
        self.factor = factor

    def forward(self, values):
        return values * self.factor

    def inverse(self, values):
        return values / self.factor


@dataclass
class Frame:
    fig: object
    axes: list
    right: list  # a RightScale per panel, or None
    bare: dict  # each panel's and the figure's own artists, before a run drew on them
    zooms: list  # beside each panel, its enlarged burst of events (same vertical scale); empty without one

    def empty(self) -> None:
        """Take away what a run drew, and let the panels scale to the next run's data."""
        for holder, bare in self.bare.items():
            for artist in list(holder.get_children()):
                if artist not in bare:
                    artist.remove()
        for ax in self.axes + self.zooms:
            ax.relim()  # the data limits of what is left: none
            ax.set_autoscale_on(True)


def new_frame(plt, spec: FrameSpec) -> Frame:
    columns = 2 if spec.zoom else 1
    fig, grid = plt.subplots(len(spec.heights), columns, sharex="col", sharey="row", squeeze=False,
                             layout=spec.layout, figsize=spec.figsize, height_ratios=list(spec.heights), dpi=DPI)
    axes, zooms = list(grid[:, 0]), list(grid[:, 1]) if spec.zoom else []
    for zoom in zooms:  # the panel's scale, read off the panel on its left
        zoom.tick_params(axis="y", labelleft=False)
    right = []
    for ax, label in zip(zooms or axes, spec.right):  # the scale on the right of the row
        if label is None:
            right.append(None)
            continue
        scale = RightScale()
        ax.secondary_yaxis("right", functions=(scale.forward, scale.inverse)).set_ylabel(label)
        right.append(scale)
    return Frame(fig, axes, right, {holder: set(holder.get_children()) for holder in (fig, *axes, *zooms)}, zooms)


class FreshFrames:
    """A new frame for every figure, closed once it is saved (``hoistsim plot``, ``hoistsim run --plot``)."""

    def frame(self, plt, spec: FrameSpec) -> Frame:
        return new_frame(plt, spec)

    def done(self, plt, fig) -> None:
        plt.close(fig)


class KeptFrames(FreshFrames):
    """The last frame of one run or a few kept for the next figure of the same spec (``hoistsim watch``).

    A family of runs is laid out by matplotlib's constrained layout around its colour bar: always afresh.
    """

    def __init__(self):
        self._spec: FrameSpec | None = None
        self._frame: Frame | None = None

    def frame(self, plt, spec: FrameSpec) -> Frame:
        if spec.layout is not None:
            return new_frame(plt, spec)
        if spec == self._spec and self._frame is not None:
            self._frame.empty()
            self._frame.fig.set_size_inches(spec.figsize)  # the last figure was made taller for its events' names
            return self._frame
        if self._frame is not None:
            plt.close(self._frame.fig)
        self._spec, self._frame = spec, new_frame(plt, spec)
        return self._frame

    def done(self, plt, fig) -> None:
        if self._frame is None or fig is not self._frame.fig:
            plt.close(fig)

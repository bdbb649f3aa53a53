"""A figure of runs laid out from its texts, each measured once.

matplotlib's constrained layout measures every axis's ticks twice before the figure is drawn, and
drawing measures them again: about a third of a six-panel figure's time, which ``hoistsim watch``
pays at every save.  A figure of one run or a few is a column of panels whose neighbours are known:
the y labels and tick labels on the left, a right-hand scale and a legend on the right, the title
and the events' names above, the time axis below.  Each is measured once and the panels are placed to
leave room for it.  A burst of events enlarged (:mod:`.zoom`) is a second column on the right, sharing
the rows' vertical scales: the legends and right-hand scales then stand beside it.
"""

from __future__ import annotations

PAD = 0.06  # in: from the figure's edges, and between a text and what it sits beside
BETWEEN = 0.12  # in: from one panel to the next (they share the time axis: no tick labels between them)
BESIDE = 0.3  # in: from a panel to its enlarged burst of events on its right (their time axes' end labels apart)


def place_panels(fig, axes, heights, anchors, title, band=None, zooms=(), zoom_share=0.0) -> None:
    """Place the panels, top to bottom, their heights in the ratios ``heights``.

    ``anchors``: where each panel's legend starts, in its axes' widths from their left; ``title``: the
    figure's title, at the top left.  A legend longer than its panel gets room below the panel.  ``band``,
    called once the panels' widths are set (what is drawn in it is spaced by them), draws what stands
    between the title and the first panel (the events' names) and returns its height (in): the figure is
    made that much taller, the panels keeping their heights.  ``zooms``: a column of panels beside them
    (a burst of events enlarged), ``zoom_share`` of the width; the legends and right-hand scales are theirs.
    """
    renderer = fig.canvas.get_renderer()
    width, height = fig.get_size_inches()

    def inches(pixels):
        return pixels / fig.dpi

    # above: the title, hung from the top edge; below: the time axis's tick labels and its label
    title.set(y=1.0 - PAD / height, va="top")
    top = PAD + inches(title.get_window_extent(renderer).height) + PAD
    below = max(inches(ax.get_window_extent(renderer).y0 - ax.xaxis.get_tightbbox(renderer).y0)
                for ax in (axes[-1], *zooms[-1:])) + PAD
    outer = list(zooms) or axes  # the panels at the right: their legends and scales beside them
    # each legend measured once: its height makes room below a short panel, its width narrows the panels
    legends = [ax.get_legend() for ax in axes]  # (placed beside the outer panel)
    boxes = [legend.get_window_extent(renderer) if legend is not None else None for legend in legends]
    tall = [inches(box.height) if box is not None else 0.0 for box in boxes]
    share = [h / sum(heights) for h in heights]

    def rows(top, height):
        room = height - top - below - BETWEEN * (len(axes) - 1)
        over = [max(0.0, t - room * s) for t, s in zip(tall, share)]
        room -= sum(over)
        placed, upper = [], height - top
        for s, extra in zip(share, over):
            placed.append((upper - room * s, room * s))
            upper -= room * s + BETWEEN + extra
        return placed

    gap = BESIDE if zooms else 0.0  # between a panel and its enlarged burst
    first = 1.0 - zoom_share if zooms else 1.0  # of the panels' width: the run's column

    def put(left, span, placed, height):
        for ax, (lower, tall_) in zip(axes, placed):
            ax.set_position([left / width, lower / height, first * span / width, tall_ / height])
        for ax, (lower, tall_) in zip(zooms, placed):
            ax.set_position([(left + first * span + gap) / width, lower / height, zoom_share * span / width,
                             tall_ / height])

    placed = rows(top, height)
    put(1.0, width - 3.0, placed, height)  # the panels' heights set the y ticks (their count follows an axis's length)
    left = align_ylabels(fig, axes) / 72.0 + max(inches(ax.yaxis.label.get_window_extent(renderer).width)
                                                 for ax in axes) + PAD
    span = width - left - gap - PAD  # the columns' widths together, the gap between them left out
    for ax, box, anchor in zip(outer, boxes, anchors):
        scale = _right_scale(ax, renderer)
        if scale:
            span = min(span, width - left - gap - inches(scale) - PAD)
        if box is not None:  # the legend starts anchor x the outer panel's width from its left
            span = min(span, (width - PAD - left - gap - inches(box.width)) / (1.0 - (1.0 - anchor) * (1.0 - first)
                                                                               if zooms else anchor))
    put(left, span, placed, height)
    above = band() if band is not None else 0.0
    if above > 0.0:
        fig.set_size_inches(width, height + above)
        title.set(y=1.0 - PAD / (height + above))
        put(left, span, rows(top + above, height + above), height + above)


def _right_scale(ax, renderer) -> float:
    """How far a panel's right-hand scale (its tick labels and label) reaches past the axes (pixels)."""
    reach = 0.0
    for child in ax.child_axes:  # a secondary axis: its limits follow the panel's when it is laid out
        child.apply_aspect()
        reach = max(reach, child.get_tightbbox(renderer).x1 - ax.get_window_extent(renderer).x1)
    return reach


def align_ylabels(fig, axes) -> float:
    """Each panel's y label the same distance left of its axes: just past the widest tick label of them all.

    Returns that distance (points).

    matplotlib's ``align_ylabels`` measures every sibling panel's tick labels again as each panel is
    drawn (n^2 measurements for n panels: a quarter of a six-panel figure's time, which ``hoistsim
    watch`` pays at every save).  Here each panel's tick texts come from its own locator and
    formatter and are measured once; half an em more keeps clear of a tick the layout may add.
    """
    from matplotlib import rcParams
    from matplotlib.font_manager import FontProperties
    from matplotlib.text import Text
    from matplotlib.transforms import offset_copy

    renderer = fig.canvas.get_renderer()
    font = FontProperties(size=rcParams["ytick.labelsize"])
    widest = 0.0
    for ax in axes:
        low, high = sorted(ax.get_ylim())
        ticks = [v for v in ax.yaxis.get_major_locator()() if low <= v <= high]
        for text in ax.yaxis.get_major_formatter().format_ticks(ticks):
            if text:
                label = Text(0, 0, text, fontproperties=font, figure=fig)
                widest = max(widest, label.get_window_extent(renderer).width)
    tick = axes[0].yaxis.majorTicks[0]
    gap = (widest * 72.0 / fig.dpi + tick.get_tick_padding() + tick.get_pad() + axes[0].yaxis.labelpad
           + 0.5 * font.get_size_in_points())
    for ax in axes:
        ax.yaxis.set_label_coords(0.0, 0.5, transform=offset_copy(ax.transAxes, fig=fig, x=-gap, units="points"))
    return gap

"""A figure of runs laid out from its texts, each measured once.

matplotlib's constrained layout measures every axis's ticks twice before the figure is drawn, and
drawing measures them again: about a third of a six-panel figure's time, which ``hoistsim watch``
pays at every save.  A figure of one run or a few is a column of panels whose neighbours are known:
the y labels and tick labels on the left, a right-hand scale and a legend on the right, the title
above, the time axis below.  Each is measured once and the panels are placed to leave room for it.
"""

from __future__ import annotations

PAD = 0.06  # in: from the figure's edges, and between a text and what it sits beside
BETWEEN = 0.12  # in: from one panel to the next (they share the time axis: no tick labels between them)


def place_panels(fig, axes, heights, anchors, title) -> None:
    """Place the panels, top to bottom, their heights in the ratios ``heights``.

    ``anchors``: where each panel's legend starts, in its axes' widths from their left; ``title``: the
    figure's title, at the top left.  A legend longer than its panel gets room below the panel.
    """
    renderer = fig.canvas.get_renderer()
    width, height = fig.get_size_inches()

    def inches(pixels):
        return pixels / fig.dpi

    # above: the title, hung from the top edge; below: the time axis's tick labels and its label
    title.set(y=1.0 - PAD / height, va="top")
    top = PAD + inches(title.get_window_extent(renderer).height) + PAD
    bottom = axes[-1]
    below = inches(bottom.get_window_extent(renderer).y0 - bottom.xaxis.get_tightbbox(renderer).y0) + PAD
    # each legend measured once: its height makes room below a short panel, its width narrows the panels
    legends = [ax.get_legend() for ax in axes]
    boxes = [legend.get_window_extent(renderer) if legend is not None else None for legend in legends]
    tall = [inches(box.height) if box is not None else 0.0 for box in boxes]
    share = [h / sum(heights) for h in heights]
    room = height - top - below - BETWEEN * (len(axes) - 1)
    over = [max(0.0, t - room * s) for t, s in zip(tall, share)]
    room -= sum(over)
    rows, upper = [], height - top
    for s, extra in zip(share, over):
        rows.append((upper - room * s, room * s))
        upper -= room * s + BETWEEN + extra

    def put(left, span):
        for ax, (lower, tall_) in zip(axes, rows):
            ax.set_position([left / width, lower / height, span / width, tall_ / height])

    put(1.0, width - 3.0)  # the panels' heights set the y ticks (their count follows an axis's length)
    left = align_ylabels(fig, axes) / 72.0 + max(inches(ax.yaxis.label.get_window_extent(renderer).width)
                                                 for ax in axes) + PAD
    span = width - left - PAD
    for ax, box, anchor in zip(axes, boxes, anchors):
        scale = _right_scale(ax, renderer)
        if scale:
            span = min(span, width - left - inches(scale) - PAD)
        if box is not None:
            span = min(span, (width - PAD - left - inches(box.width)) / anchor)
    put(left, span)


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

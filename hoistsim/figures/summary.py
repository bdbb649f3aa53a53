"""A sweep's summary against the swept value: what a designer compares, a panel per summary an element gives.

Runs of a kind apart (a clutch that never locks, one that never slips) are
bands across every panel, so that "never locks" is never read as a lock-up
time of zero and ten thousand runs draw as a few bands, not a wall of marks;
with few runs they are also marked where the value would be.  A value that
means something else for such a run (the heat of a clutch that never locks is
the heat up to the end of the run) is drawn as open points and said so.
"""

from __future__ import annotations

import numpy as np

from ..display import DISPLAYS
from ..display.part_names import under_part_names
from ..results.part_names import names_table
from .base import flat_where_round_off, swept_label

POINTS = 60  # up to this many runs, each is a marked point
MARKER = 6  # pt: the marker of a kind of run (never locks)


def summary_figure(summaries, swept, plt, name: str = "", parameters: dict | None = None):
    # the summaries under their parts' own names too (a hoist's lockup_time is its clutch's clutch_lockup_time)
    table = names_table(parameters or {})
    summaries = [under_part_names(row, table) for row in summaries]
    names = set(summaries[0])
    # variants of one part (a load on a rigid or an elastic rope) share their panels: each is drawn once
    panels = sorted(dict.fromkeys(p for display in DISPLAYS for p in display.summary_panels_of(summaries[0])
                                  if p.name in names), key=lambda p: p.order)
    outcomes = [(o, _applies(o, summaries)) for o in dict.fromkeys(o for display in DISPLAYS
                                                                   for o in display.outcomes_of(summaries[0]))]
    outcomes = [(o, mask) for o, mask in outcomes if mask is not None and mask.any()]
    from matplotlib.transforms import offset_copy

    x = np.asarray(swept[1], dtype=float)
    order = np.argsort(x, kind="stable")
    columns = 2 if len(panels) > 1 else 1
    rows = -(-len(panels) // columns)
    fig, axes = plt.subplots(rows, columns, sharex=True, squeeze=False, layout="constrained",
                             figsize=(5.4 * columns, 0.9 + 2.6 * rows))
    few = len(summaries) <= POINTS

    for ax, panel in zip(axes.flat, panels):
        y = np.asarray([row[panel.name] for row in summaries], dtype=float) * panel.scale + panel.offset
        partial = (np.isnan(np.asarray([row[panel.partial_of] for row in summaries], dtype=float))
                   if panel.partial and panel.partial_of in names else np.zeros(len(x), bool))
        ax.plot(x[order], y[order], color="#1f4e79", lw=1.4, zorder=2)
        if few:
            ax.plot(x[~partial], y[~partial], "o", color="#1f4e79", ms=4, zorder=3)
        if partial.any():
            ax.plot(x[partial], y[partial], "o", mfc="white", mec="#b2182b", ms=4 if few else 2.5,
                    zorder=3, label=f"{panel.ylabel.split(' [')[0]} of a run that never locks: "
                                      f"{panel.partial}")
        for outcome, mask in outcomes:
            _band(ax, x, order, mask, outcome.colour)
            if few and np.isnan(y[mask]).all():  # where the value is none (no lock-up), marked at the top:
                # hung from the panel's top edge by its half height and a little, so that none of it is cut off
                top = offset_copy(ax.get_xaxis_transform(), fig=fig, y=-(0.5 * MARKER + 1.5), units="points")
                ax.plot(x[mask], np.ones(mask.sum()), outcome.marker, color=outcome.colour, ms=MARKER, transform=top,
                        zorder=4)
            elif few and panel.order == 0:
                ax.plot(x[mask], y[mask], outcome.marker, color=outcome.colour, ms=MARKER, zorder=4)
        if panel.beside is not None and panel.beside[1] in names:  # another answer to the same question
            other = np.asarray([row[panel.beside[1]] for row in summaries], dtype=float) * panel.scale + panel.offset
            ax.plot(x[order], other[order], color="#b35806", lw=1.2, ls="--", marker="s" if few else None, ms=3.5,
                    zorder=2, label=panel.beside[0])
        if panel.zero_line:
            ax.axhline(0.0, color="k", lw=0.6)
        swept_limit = panel.limit is not None and panel.limit[1] in summaries[0]  # a swept key is a column
        limit = _given(parameters or {}, panel.limit[1]) if panel.limit and not swept_limit else None
        if limit is not None:
            value = limit * panel.scale + panel.offset
            ax.axhline(value, color="0.25", ls=":", lw=1.0, zorder=1,
                       label=f"{panel.limit[0]} ({value:.4g} {panel.ylabel.rsplit('[', 1)[-1].rstrip(']')})")
        flat_where_round_off(ax, [y])
        ax.set_ylabel(panel.ylabel)
        ax.grid(True, lw=0.4, alpha=0.6)
    for ax in axes.flat[len(panels):]:
        ax.set_visible(False)
    for ax in axes[-1]:
        ax.set_xlabel(swept_label(swept))
    if len(panels) % columns:  # the last row's empty cell: the panel above carries the swept axis's labels
        axes[-2][-1].xaxis.set_tick_params(labelbottom=True)
        axes[-2][-1].set_xlabel(swept_label(swept))

    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    # a kind of run: its band, and where the runs are few enough to be marked one by one, its marker on it
    handles = [(Patch(facecolor=o.colour, alpha=0.18),) + ((Line2D([], [], ls="", marker=o.marker, color=o.colour,
                                                                   ms=MARKER),) if few else ()) for o, _ in outcomes]
    labels = [f"{o.label} ({int(m.sum())} of {len(m)} runs)" for o, m in outcomes]
    for ax in axes.flat:
        for handle, label in zip(*ax.get_legend_handles_labels()):
            handles.append(handle)
            labels.append(label)
    fig.suptitle(f"{name}: {len(summaries)} runs against {swept_label(swept)}",
                 fontsize=11, x=0.01, ha="left")
    if handles:
        from matplotlib.legend_handler import HandlerTuple

        fig.legend(handles, labels, loc="outside lower center", ncols=min(len(handles), 2), fontsize=8,
                   frameon=False, handler_map={tuple: HandlerTuple(ndivide=1)})
    return fig


def _given(parameters: dict, key: str):
    """A dotted key's value in the resolved scenario, None where the scenario does not give it."""
    for part in key.split("."):
        parameters = parameters.get(part) if isinstance(parameters, dict) else None
    return parameters


def _applies(outcome, summaries):
    try:
        return np.asarray([bool(outcome.applies(row)) for row in summaries])
    except KeyError:  # the runs have not the part this outcome is about
        return None


def _band(ax, x, order, mask, colour):
    """Shade the swept range of each stretch of neighbouring runs of one kind (halfway to the next run)."""
    xs, flags = x[order], mask[order]
    edges = np.concatenate([[xs[0]], 0.5 * (xs[1:] + xs[:-1]), [xs[-1]]])
    start = None
    for i, flag in enumerate(np.append(flags, False)):
        if flag and start is None:
            start = i
        elif not flag and start is not None:
            low, high = edges[start], edges[i]
            if high == low:  # a single run at an end of the range: a visible sliver
                span = (xs[-1] - xs[0]) or 1.0
                low, high = low - 0.005 * span, high + 0.005 * span
            ax.axvspan(low, high, color=colour, alpha=0.15, lw=0, zorder=0)
            start = None

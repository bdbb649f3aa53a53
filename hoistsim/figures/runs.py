"""The runs of a file against time: a panel per question, each contributed by the element that answers it.

One run: each curve in its own colour, the phases (clutch open, brake holding,
clutch locked) shaded in every panel, the events drawn in every panel and
named once above them (:mod:`.naming`), a burst of them in a sliver of the run
enlarged in a column of panels beside (:mod:`.zoom`), the dots on the curves
whole inside their panels (:mod:`.marks`).  Two to four runs: a colour per run, events drawn in
the run's colour with a line style per kind.  More: a colour-mapped family by
the swept value, with no event lines (the lock instants are dots on the slip
curves), drawn as one collection per curve and thinned to what the figure can
show, so a thousand runs draw in seconds.  Legends sit outside the panels.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from ..display import DISPLAYS, headline
from ..switch_kinds import SWITCH_KINDS
from .base import colour_scale, flat_where_round_off, row_text, swept_label
from .frames import FrameSpec, FreshFrames
from .marks import draw_marks, time_limits
from .naming import name_events, wrap_title
from .placing import align_ylabels, place_panels
from .read_back import parameters_of, prepared
from .zoom import SHARE as ZOOM_SHARE
from .zoom import burst_window
from .zoom import time_axis as zoom_time_axis

FEW = 4  # more runs than this are drawn as a colour-mapped family
MAX_EVENT_LINES = 40  # a run with more events than this (periodic stick-slip) has its events listed, not drawn
THIN_TO = 600  # in a family, a curve longer than 2 x this many rows is thinned to its extremes per bucket
QUIET = ("observation", "cycle")  # categories of instant drawn as no line: rows, not events

_TRACE_COLOURS = ("#1f4e79", "#c1440e", "#2a7f62", "#6a3d9a", "#b8860b", "#17becf", "#8c564b", "#e377c2")
_LIMIT_COLOUR = "0.35"
_EVENT_STYLE = {"lock": ("#1b7837", "-"), "unlock": ("#b2182b", "--"), "reversal": ("#762a83", ":"),
                "brake_release": ("#8c510a", "-."), "engage": ("#2166ac", (0, (1, 1))),
                "disengage": ("#2166ac", (0, (3, 1, 1, 1)))}
_CURVE = "curve"  # the gid of a run's curve (not a zero line, an event line or a legend's sample)
_LEGEND = dict(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8, frameon=False, borderaxespad=0.0)


def runs_figure(runs, plt, swept, frames=None):
    """The figure of ``runs``; ``frames`` gives its frame (:mod:`.frames`: afresh, or kept by ``watch``)."""
    for run in runs:  # what traces read beside the columns (a limit the scenario gives), under the parts' names
        prepared(run)
    present = set(runs[0])
    panels = _panels(present, runs[0])
    shading = list(dict.fromkeys(phase for display in DISPLAYS for phase in display.shading_of(runs[0])
                                 if phase.column in present))

    heights = [panel.height for panel in panels]
    mode = "one" if len(runs) == 1 else "few" if len(runs) <= FEW else "family"
    scales = [_right_scale(panel, runs[0]) for panel in panels]
    start, end = min(r["time"][0] for r in runs), max(r["time"][-1] for r in runs)
    # one run's burst of events in a sliver of its time: enlarged in a column of its own
    window = burst_window(_event_times(runs[0]), start, end) if mode == "one" else None
    # a family's colour bar is placed by matplotlib's layout; a run or a few, from their texts measured once
    frame = (frames or FreshFrames()).frame(plt, FrameSpec(
        heights=tuple(heights), figsize=(11, 0.9 + 1.9 * sum(heights)),
        layout="constrained" if mode == "family" else None,
        right=tuple(scale[0] if scale else None for scale in scales), zoom=window is not None))
    fig, axes, zooms = frame.fig, frame.axes, frame.zooms
    share = ZOOM_SHARE if zooms else 1.0  # of the panels' width: the panels the legends stand beside
    for right, scale in zip(frame.right, scales):
        if scale:
            right.factor = scale[1]
    run_colours, cmap, norm = colour_scale(swept[1], plt) if mode != "one" else ([None], None, None)

    marked = []  # the times of the dots on the curves
    for ax, panel in zip(axes, panels):
        marked += _draw_panel(ax, panel, runs, run_colours, mode, plt)
    for zoom, panel in zip(zooms, panels):
        _draw_panel(zoom, panel, runs, run_colours, mode, plt)
    if mode == "one":
        _shade(axes + zooms, runs[0], shading)
    labels = _draw_events(axes + zooms, runs, run_colours, mode) if mode != "family" else []

    for ax, panel in zip(axes, panels):
        ax.set_ylabel(panel.ylabel)
        ax.grid(True, lw=0.4, alpha=0.6)
        if panel.zero_line:
            ax.axhline(0.0, color="k", lw=0.6)
        _no_round_off_zoom(ax)
        entries = {}  # one entry a label: every clutch's locks are one kind of mark
        for handle, label in zip(*ax.get_legend_handles_labels()):
            entries.setdefault(label, handle)
        if entries:  # beside the row (right of an enlarged burst), past the right-hand scale where there is one
            outer = zooms[axes.index(ax)] if zooms else ax
            ax.legend(list(entries.values()), list(entries), bbox_transform=outer.transAxes,
                      **{**_LEGEND, "bbox_to_anchor": (_legend_anchor(panel, share), 1.0)})
    for zoom, panel in zip(zooms, panels):
        zoom.grid(True, lw=0.4, alpha=0.6)
        if panel.zero_line:
            zoom.axhline(0.0, color="k", lw=0.6)
    axes[-1].set_xlabel("time [s]")
    axes[-1].set_xlim(*time_limits(start, end, marked))
    if zooms:
        zoom_time_axis(zooms[-1], window)
    title = fig.suptitle(_title(runs, swept), fontsize=11, x=0.01, ha="left")
    if mode == "family":
        align_ylabels(fig, axes)
        bar = fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=axes, location="top",
                           shrink=0.45, aspect=45, pad=0.01)
        bar.set_label(swept_label(swept), fontsize=9)
    else:
        place_panels(fig, axes, heights, [_legend_anchor(panel, share) for panel in panels], title,
                     band=lambda: _name(fig, axes[0], zooms[0] if zooms else None, labels, window),
                     zooms=zooms, zoom_share=ZOOM_SHARE)
    return fig


def _name(fig, ax, zoom, labels, window) -> float:
    """Name the events above the first panel, and those of an enlarged burst above its own panel (named once
    in the run's: how many, and where they are enlarged); returns the height the names take (in)."""
    if zoom is None:
        return name_events(fig, ax, labels)
    inside = [label for label in labels if window[0] <= label[0] <= window[1]]
    outside = [label for label in labels if not window[0] <= label[0] <= window[1]]
    burst = (inside[-1][0], f"{len(inside)} events, enlarged \u2192", "0.2")
    return max(name_events(fig, ax, outside + [burst]), name_events(fig, zoom, inside))


def _event_times(run) -> list[float]:
    """The instants one run's figure draws as lines (none where it has too many to draw)."""
    times = [float(row["time"]) for row in run["events"] if row_text(row, "category") not in QUIET]
    return times if len(times) <= MAX_EVENT_LINES else []


def _legend_anchor(panel, share=1.0) -> float:
    """Where a panel's legend starts, in its (outer) axes' widths from their left: past a right-hand scale.

    ``share``: those axes' share of the figure's panels' width (an enlarged burst's column: a third)."""
    return 1.0 + (0.13 if panel.right_axis else 0.01) / share


def _panels(present, run):
    """The parts' panels merged by name, each with the curves the file has columns for, top first."""
    merged = {}
    for display in DISPLAYS:
        for panel in display.panels_of(run):
            traces = tuple(t for t in panel.traces if all(c in present for c in t.columns()))
            if panel.name in merged:
                first = merged[panel.name]
                merged[panel.name] = replace(first, traces=first.traces + traces,
                                             right_axis=first.right_axis or panel.right_axis)
            else:
                merged[panel.name] = replace(panel, traces=traces)
    return sorted((p for p in merged.values() if p.traces), key=lambda p: p.order)


def _draw_panel(ax, panel, runs, run_colours, mode, plt) -> list[float]:
    """Draw a panel's curves and their dots; returns the dots' times."""
    marked = []
    curves = [t for t in panel.traces if not t.limit]
    several = len(panel.traces) > 1
    for trace in panel.traces:
        if mode == "family" and trace.limit:
            continue  # a capacity per run would bury the family
        if mode == "family":
            _family(ax, trace, panel.scale, runs, run_colours)
        else:
            drawn = False
            for run, colour in zip(runs, run_colours):
                values = trace.of(run)
                if values is None:
                    continue
                drawn = True
                if mode == "one":
                    colour = _LIMIT_COLOUR if trace.limit else _TRACE_COLOURS[curves.index(trace) % len(_TRACE_COLOURS)]
                    label = trace.label
                else:
                    label = None
                ax.plot(run["time"], values * panel.scale, color=colour, ls=trace.style,
                        lw=0.9 if trace.limit else 1.5, alpha=0.75 if trace.limit and mode == "few" else 1.0,
                        label=label, gid=_CURVE)
            if mode == "few" and several and drawn:  # the runs' colours are in the top legend; here, which curve is which
                ax.plot([], [], color="0.3", ls=trace.style, lw=0.9 if trace.limit else 1.5, label=trace.label)
        marked += draw_marks(ax, trace, panel.scale, runs, run_colours, mode)
    if mode == "family" and several:
        for trace in curves:
            ax.plot([], [], color="0.3", ls=trace.style, lw=1.2, label=trace.label)
    return marked


def _family(ax, trace, scale, runs, run_colours):
    """Every run's curve in one collection, in the run's colour, thinned to the figure's resolution."""
    from matplotlib.collections import LineCollection

    segments, colours = [], []
    for run, colour in zip(runs, run_colours):
        values = trace.of(run)
        if values is None:
            continue
        t, y = _thin(run["time"], values * scale)
        segments.append(np.column_stack([t, y]))
        colours.append(colour)
    lines = LineCollection(segments, colors=colours, linestyles=trace.style,
                           linewidths=0.6 if len(segments) > 100 else 1.0, alpha=0.6 if len(segments) > 100 else 0.9)
    ax.add_collection(lines)
    ax.autoscale_view()


def _thin(t, y):
    """At most about 2 x THIN_TO points: each bucket's lowest and highest, in time order (peaks survive)."""
    if len(t) <= 2 * THIN_TO:
        return t, y
    size = -(-len(t) // THIN_TO)
    padded = np.concatenate([y, np.full(size * THIN_TO - len(y), y[-1])]).reshape(THIN_TO, size)
    offsets = np.arange(THIN_TO) * size
    index = np.sort(np.concatenate([[0, len(t) - 1], offsets + padded.argmin(axis=1),
                                     offsets + padded.argmax(axis=1)]))
    index = index[np.append(True, index[1:] != index[:-1]) & (index < len(t))]
    return t[index], y[index]


def _shade(axes, run, shading):
    """Each phase of the run (clutch open, brake holding, clutch locked) shaded across every panel."""
    time = np.asarray(run["time"], dtype=float)
    for phase in shading:
        where = np.asarray(run[phase.column]) == phase.value
        # a phase of a row alone (a rope slack at the first instant only) shades nothing a reader could see:
        # no legend entry either
        if np.diff(time)[where[:-1]].sum() <= 1e-3 * (time[-1] - time[0]):
            continue
        for ax in axes:
            ax.fill_between(run["time"], 0, 1, where=where, transform=ax.get_xaxis_transform(), step="post",
                            facecolor="none" if phase.hatch else phase.colour, edgecolor=phase.colour,
                            hatch=phase.hatch, alpha=0.35 if phase.hatch else 0.12, lw=0,
                            label=phase.label if ax is axes[0] else None)


def _event_text(row) -> str:
    """What a line's label says: a coupling's switch of the core's kinds names the coupling ("mesh unlock"); a
    switch its part renamed ("rope taut", "lift off") and a scheduled event name themselves ("brake release")."""
    kind = _kind(row)
    text = f"{row_text(row, 'element')} {kind}" if row_text(row, "category") == "switch" and kind in SWITCH_KINDS \
        else kind
    return text.replace("_", " ")


def _draw_events(axes, runs, run_colours, mode):
    """Switches, scheduled instants and limits crossed as lines in every panel; named at the top (one run) or
    by style.  Observations (a peak, a lowest point) and the ends of cycles get none: they are rows."""
    seen, labels = set(), []  # labels: (time, text, colour) of one run's events, named once the panels are placed
    for run, colour in zip(runs, run_colours):
        rows = [(float(row["time"]), _kind(row), _event_text(row)) for row in run["events"]
                if row_text(row, "category") not in QUIET]
        if len(rows) > MAX_EVENT_LINES:
            axes[0].annotate(f"{len(rows)} switches: listed in the file's events, not drawn",
                             (0.01, 0.02), xycoords="axes fraction", fontsize=8, color="0.3")
            continue
        for time, kind, text in rows:
            kind_colour, style = _EVENT_STYLE.get(kind, ("#888888", ":"))
            for ax in axes:
                ax.axvline(time, color=kind_colour if mode == "one" else colour, ls=style, lw=0.9, alpha=0.75)
            if mode == "one":
                labels.append((time, text, kind_colour))
            elif kind not in seen:
                axes[0].plot([], [], color="0.3", ls=style, lw=0.9, label=f"event: {kind.replace('_', ' ')}")
            seen.add(kind)
    if mode == "few":
        for run, colour in zip(runs, run_colours):
            axes[0].plot([], [], color=colour, lw=3, label=_run_name(run))
    return labels


def _no_round_off_zoom(ax):
    """A quantity constant to round-off (a steady lift's speed, a locked clutch's slip) is shown flat
    (:func:`.base.flat_where_round_off`)."""
    from matplotlib.collections import LineCollection

    drawn = [line.get_ydata() for line in ax.get_lines() if line.get_gid() == _CURVE]
    drawn += [c.get_datalim(ax.transData).intervaly for c in ax.collections if isinstance(c, LineCollection)]
    flat_where_round_off(ax, drawn)


def _right_scale(panel, run) -> tuple[str, float] | None:
    """A panel's right-hand scale for this run: its label and its factor, None where it has none."""
    if panel.right_axis is None:
        return None
    label, factor_of = panel.right_axis
    try:
        return label, float(factor_of(parameters_of(run)))
    except (KeyError, TypeError, ValueError):
        return None  # the scene has not the part that gives this scale


def _title(runs, swept) -> str:
    attrs = runs[0]["attrs"]
    name = str(attrs.get("name", ""))
    if len(runs) > 1:
        return f"{name}: {len(runs)} runs, coloured by {swept_label(swept)}"
    said = headline({**attrs, "events": runs[0]["events"]})  # the events: each clutch's story
    if not said:  # no part has a story to tell (two inertias on springs): what the scene is, as its file says
        description = " ".join(str(parameters_of(runs[0]).get("description") or "").split())
        said = [description] if description else []
    return wrap_title(name, said)


def _run_name(run) -> str:
    label = str(run["attrs"].get("label", run["attrs"].get("name", "")))
    return label.split("=", 1)[-1] if "=" in label else label


def _kind(row) -> str:
    return row_text(row, "kind")

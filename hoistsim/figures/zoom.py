"""A burst of events in a short window of a long run, enlarged in panels of its own beside the run's.

A compliant shaft rings: the clutch slips and relocks seven times in the first 30 ms of a 1 s run, a sliver
of the time axis where the lines crowd and the names must merge.  Where at least ``BURST`` events fall
within ``NARROW`` of the time axis, a column of panels beside the run's shows that window (the same
curves, on the same vertical scales), with each event's line and name.
"""

from __future__ import annotations

BURST = 4  # events: at least this many ...
NARROW = 0.05  # ... within this share of the time axis are a burst
SHARE = 0.3  # of the panels' width: the enlarged column's
MARGIN = 0.15  # of the burst's own length: shown either side of it
NEAR = 0.5  # of the burst's own length: from the run's start or end, the window reaches it (the ringing's start)


def burst_window(times, start: float, end: float) -> tuple[float, float] | None:
    """The window (s) enlarged for the events at ``times`` of a run from ``start`` to ``end``: the longest
    run of events within ``NARROW`` of the axis, where it has ``BURST`` or more; None where there is none."""
    times = sorted(times)
    span = end - start
    best = None
    for i in range(len(times)):
        j = i
        while j + 1 < len(times) and times[j + 1] - times[i] <= NARROW * span:
            j += 1
        if j + 1 - i >= BURST and (best is None or j - i > best[1] - best[0]):
            best = (i, j)
    if best is None:
        return None
    first, last = times[best[0]], times[best[1]]
    pad = max(MARGIN * (last - first), 1e-3 * span)
    low = start if first - start <= NEAR * (last - first) else first - pad
    high = end if end - last <= NEAR * (last - first) else last + pad
    return low, high


def time_axis(ax, window) -> None:
    """The enlarged column's time axis: its window, in ms where it is shorter than a second."""
    from matplotlib.ticker import FuncFormatter, ScalarFormatter

    ax.set_xlim(*window)
    if window[1] - window[0] < 1.0:
        ax.xaxis.set_major_formatter(FuncFormatter(lambda seconds, _: f"{1000 * seconds:g}"))
        ax.set_xlabel("time [ms], enlarged")
    else:  # (a frame kept from a run whose burst was in ms)
        ax.xaxis.set_major_formatter(ScalarFormatter())
        ax.set_xlabel("time [s], enlarged")

"""The texts of a run's figure that must not run into each other: its events' names at the top, its title.

An event's name stands upright above the first panel, beside where its line meets the panel's top: in a
band of its own, so that no name is written over a curve or crossed by another event's line.  Two events
closer than a name's width (two clutches switching in the same millisecond, a clutch locking as another
engages) would write over each other: one is named on the left of its line, or where neither side has room
their names are merged into one, beside the last of their lines ("clutch3 engage / clutch1 lock").  Two names
side by side stand a name's width apart, so that neither reads as touching the other.  The title says each
part's headline; a drivetrain of several clutches says more than a line holds, so it is wrapped between the
parts' headlines.
"""

from __future__ import annotations

import textwrap

FONT = 7.0  # pt: an event's name
BESIDE = 2.0  # pt: from its line to its name
APART = FONT  # pt: between two names, a name's width: two neighbours read as two, not one touching the other
ABOVE = 2.0  # pt: from the panel's top to its names
SHARED_SPAN = 3.0  # a shared name's events lie within this many names' widths
LONGEST = 44  # characters of a shared name; beyond, its first event's and a count
TITLE_CHARACTERS = 125  # a title's line at most (11 pt, on a figure 11 in wide)


def name_events(fig, ax, labels) -> float:
    """Name the events ``labels`` ((time, text, colour)) above ``ax``, no two names on each other; returns the
    height they take above it (in).

    Called once the panels are placed: the spacing follows the panel's width.  Each name stands beside its
    line, on its right where there is room, else on its left; events too close for either share one name
    beside the last of their lines.  The fewest shared names, then the fewest on the left (a search over
    the events in time order: a run draws at most a few dozen).
    """
    from functools import lru_cache

    low, high = ax.get_xlim()
    labels = sorted(labels, key=lambda item: item[0])
    if not labels or high <= low:
        return 0.0
    scale = ax.get_position().width * fig.get_size_inches()[0] * 72.0 / (high - low)  # pt a second
    span = (high - low) * scale
    xs = [(time - low) * scale for time, _, _ in labels]
    width = 1.2 * FONT  # an upright name's width: its line's height (its glyphs' 1.0 x FONT, and room)

    @lru_cache(maxsize=None)
    def best(i: int, free: float):
        """(cost, [(first, last, side)]) naming labels i.. with the panel free from ``free`` pt on."""
        if i == len(labels):
            return 0.0, ()
        options = []
        reach = [last for last in range(i, len(labels)) if xs[last] - xs[i] <= SHARED_SPAN * width]
        for last in reach:
            shared = 10.0 * (last - i)
            left = xs[i] - BESIDE - width
            if left >= max(free, 0.0):
                cost, rest = best(last + 1, xs[i] - BESIDE + APART)
                options.append((shared + 1.0 + cost, ((i, last, "left"),) + rest))
            right = xs[last] + BESIDE + width
            if xs[last] + BESIDE >= free and right <= span:
                cost, rest = best(last + 1, right + APART)
                options.append((shared + cost, ((i, last, "right"),) + rest))
        if not options:  # no room: they share one name on their right, over the last name
            last = reach[-1]
            cost, rest = best(last + 1, xs[last] + BESIDE + width + APART)
            options.append((1000.0 + cost, ((i, last, "right"),) + rest))
        return min(options, key=lambda option: option[0])

    names = []
    for first, last, side in best(0, -1e9)[1]:
        group = labels[first:last + 1]
        texts = list(dict.fromkeys(text for _, text, _ in group))  # a switch named twice is named once
        text = " / ".join(texts)
        if len(text) > LONGEST:
            text = f"{texts[0]} / {len(texts) - 1} more"
        if len(group) > len(texts):  # a clutch locking and letting go again and again
            text += f" ({len(group)} events)"
        colours = {colour for _, _, colour in group}
        anchor = group[0][0] if side == "left" else group[-1][0]
        names.append(ax.annotate(
            text, (anchor, 1.0), xycoords=("data", "axes fraction"), xytext=(-BESIDE if side == "left" else BESIDE,
                                                                               ABOVE), textcoords="offset points",
            fontsize=FONT, rotation=90, va="bottom", ha="right" if side == "left" else "left",
            color=colours.pop() if len(colours) == 1 else "0.2", gid="event name", annotation_clip=False))
    renderer = fig.canvas.get_renderer()
    return max(name.get_window_extent(renderer).height for name in names) / fig.dpi + ABOVE / 72.0


NO_BREAK = "\u00a0"  # within a clause of a headline: textwrap breaks at plain spaces only


def wrap_title(name: str, said: list[str]) -> str:
    """``name: headline; headline; ...`` on one line, or where it is longer than a line, as many headlines a
    line as fit (a part's headline of several, a drivetrain's clutches, split between them; one longer than a
    line wrapped between its clauses: "locks at 0.791 s" is never split)."""
    parts = [part for text in said for part in text.split("; ")]
    if not parts:
        return name
    lines, current = [], f"{name}: {parts[0]}"
    for part in parts[1:]:
        if len(current) + 2 + len(part) <= TITLE_CHARACTERS:
            current = f"{current}; {part}"
        else:
            lines.append(current + ";")
            current = part
    lines.append(current)
    kept = [", ".join(clause.replace(" ", NO_BREAK) for clause in line.split(", ")) for line in lines]
    return "\n".join(piece.replace(NO_BREAK, " ") for line in kept
                     for piece in textwrap.wrap(line, TITLE_CHARACTERS, subsequent_indent="    "))

"""A guard's identity: the section it belongs to and its kind, made here and nowhere else.

The loop looks guards up by name (the masks of a pass, what is taken off each
guard, which ones ended the last pass): every such name is a :class:`GuardId`,
made from a section and a kind and read back by its parts, never formatted or
split elsewhere.  It is a string, so that a pass's dictionaries keyed by guard
(JAX pytrees, their keys sorted) keep the order and the program they have as
plain names.
"""

from __future__ import annotations

# the kinds of a switching coupling's guards (see switching)
SLIP = "slip"
BREAKAWAY_FORWARD = "breakaway+"
BREAKAWAY_BACKWARD = "breakaway-"
SLIP_PEAK = "slip_peak"
SLIP_VALLEY = "slip_valley"
MARGIN_VALLEY = "margin_valley"
# a coupling whose capacity differs with the way it is pushed: a margin valley each way (see switching)
MARGIN_VALLEYS_EACH_WAY = ("margin_valley+", "margin_valley-")
# a knot coordinate's two guards: the next knot ahead of where the pass started, and the one behind
AHEAD, BEHIND = "+", "-"


class GuardId(str):
    """``"<section>.<kind>"``: a coupling's or an element's guard (an element's observation, a knot's side)."""

    __slots__ = ()

    def __new__(cls, section: str, kind: str):
        return super().__new__(cls, f"{section}.{kind}")

    def __getnewargs__(self) -> tuple[str, str]:
        return self.section, self.kind

    @property
    def section(self) -> str:
        return self.rpartition(".")[0]

    @property
    def kind(self) -> str:
        return self.rpartition(".")[2]


def knot_guards(section: str, kink: str) -> tuple[GuardId, GuardId]:
    """The guards of an element's knot coordinate ``kink``: the knot ahead, the knot behind."""
    return GuardId(section, kink + AHEAD), GuardId(section, kink + BEHIND)

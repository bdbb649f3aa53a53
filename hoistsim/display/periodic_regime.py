"""The periodic regime: its degree of irregularity."""

from __future__ import annotations

from .panel import Display, SummaryPanel


def _headline(summary: dict) -> str | None:
    delta = float(summary["irregularity"])
    return "periodic regime not settled" if delta != delta else f"delta = {delta:.4g} in the settled regime"


PERIODIC_REGIME = Display(
    summary_panels=(SummaryPanel("irregularity", "degree of irregularity delta\n(settled regime)", 60),),
    headline=_headline)

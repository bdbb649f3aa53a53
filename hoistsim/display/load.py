"""The load: its height (its lowest point marked) and its speed; where it ends."""

from __future__ import annotations

from .panel import Display, Panel, SummaryPanel, Trace


def _headline(summary: dict) -> str | None:
    final, lowest = float(summary["final_load_position"]), float(summary["lowest_load_position"])
    # a load a speed controller moves goes where it is asked (lowered on purpose); its brake sequence says any
    # rollback: only an uncontrolled hoist's load below its start has run back
    controlled = any(key.endswith("_saturated_time") for key in summary)
    if float(summary.get("peak_buffer_force", 0.0)) > 0.0:  # brought down onto its buffer: where it stopped
        return f"load comes down {-lowest:.3g} m onto its buffer, ends {final:+.3g} m"
    if controlled and final < 0:
        return f"load lowered {-final:.3g} m"
    if lowest < 0 and final < 0:
        return f"load runs back {-final:.3g} m"
    if lowest < 0:
        return f"load dips {-lowest:.3g} m, ends {final:+.3g} m"
    return f"load {final:+.3g} m"


LOAD = Display(
    panels=(
        Panel("load_position", "load height [m]\n(above its start)", 30,
              (Trace("load", "load_position", lowest="lowest point"),), zero_line=True, height=0.8),
        Panel("load_velocity", "load speed [m/s]\n(+ up)", 31, (Trace("load", "load_velocity"),),
              zero_line=True, height=0.8),
    ),
    summary_panels=(
        SummaryPanel("lowest_load_position", "lowest load position [m]", 30, zero_line=True),
        SummaryPanel("final_load_position", "load position at the end [m]", 31, zero_line=True),
    ),
    headline=_headline,
)

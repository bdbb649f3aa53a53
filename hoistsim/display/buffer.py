"""A buffer under the load: the force it stops the load with, its contact phases, its peak against the standard's."""

from __future__ import annotations

from .panel import Display, Panel, Phase, SummaryPanel, Trace


def _headline(summary: dict) -> str | None:
    peak = float(summary["peak_buffer_force"])
    if not peak > 0.0:
        return "load never reaches the buffer"
    return (f"buffer peaks at {peak / 1000:.3g} kN, pressed {float(summary['peak_buffer_compression']) * 1000:.3g} mm "
            f"(EN 13001-2 phi7: {float(summary['buffer_force_standard']) / 1000:.3g} kN)")


BUFFER = Display(
    panels=(Panel("buffer", "buffer force [kN]", 33, (
        Trace("buffer force", "buffer_force", marks=("contact", "separation", "buffer_force_peak")),),
        scale=1e-3, zero_line=True),),
    shading=(Phase("load on the buffer", "buffer_contact", 1, "#5aae61", hatch="\\\\"),),
    summary_panels=(
        SummaryPanel("peak_buffer_force", "peak buffer force [kN]", 34, scale=1e-3,
                     beside=("EN 13001-2's phi7 design force", "buffer_force_standard")),
        SummaryPanel("peak_buffer_compression", "peak buffer compression [mm]", 35, scale=1e3),
    ),
    headline=_headline,
)

"""An elastic rope: its force against the load's weight, its slack phases, its peak and dynamic factor."""

from __future__ import annotations

import numpy as np

from .panel import Display, Panel, Phase, SummaryPanel, Trace


def _weight_line(run):
    """The load's weight across the run (N): where the rope force lifts it off the ground."""
    parameters = run["parameters"]
    load = parameters.get("load") or parameters["drivetrain"]["load"]  # the hoist's, or a drawn drivetrain's
    return np.full(np.shape(run["rope_force"]), load["mass"] * parameters["gravity"])


def _headline(summary: dict) -> str | None:
    return (f"peak rope force {float(summary['peak_rope_force']) / 1000:.3g} kN "
            f"(x{float(summary['dynamic_factor']):.3f} M g)")


ROPE = Display(
    panels=(Panel("rope", "rope force [kN]", 32, (
        Trace("rope force", "rope_force", marks=("lift_off", "touch_down", "rope_force_peak")),
        Trace("load weight M g", "rope_force", style=":", limit=True, value=_weight_line),
    ), scale=1e-3, zero_line=True),),
    shading=(Phase("rope slack", "rope_taut", 0, "#fdb863", hatch="//"),),
    summary_panels=(
        SummaryPanel("peak_rope_force", "peak rope force [kN]", 32, scale=1e-3),
        SummaryPanel("dynamic_factor", "dynamic factor\n(peak rope force / M g)", 33,
                     beside=("EN 13001-2's phi2 at the lift-off rope speed", "dynamic_factor_standard")),
    ),
    headline=_headline,
)

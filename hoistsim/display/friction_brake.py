"""A brake that slips: its static torque beside the holding brake's panel (which it shares), its heat."""

from __future__ import annotations

from .panel import Display, Panel, SummaryPanel, Trace


def _headline(summary: dict) -> str | None:
    heat = float(summary["brake_energy"])
    return f"brake heat {heat / 1000:.2f} kJ" if heat > 0 else None


# its torque and phase are the holding brake's (holding_brake.py: drawn once), its static torque beside them
FRICTION_BRAKE = Display(
    panels=(Panel("brake", "brake torque [N*m]\n(at the drum)", 40, (
        Trace("static torque", "brake_capacity", style=":", limit=True),
        # a load lifted against the brake meets the capacity's other side
        Trace("- static torque", "brake_capacity", style=":", limit=True, needs=("brake_capacity", "brake_torque"),
              value=lambda run: -run["brake_capacity"] if (run["brake_torque"] < 0).any() else None),
    ), zero_line=True, height=0.8),),
    summary_panels=(SummaryPanel("brake_energy", "brake heat [kJ]", 40, scale=1e-3),),
    headline=_headline,
    names_part=("brakes", "brake"),
)

"""The hoist's cone clutch: the clutch output's speed, its slip, its torque against its capacity, its phases."""

from __future__ import annotations

import numpy as np

from .panel import Display, Outcome, Panel, Phase, SummaryPanel, Trace, speed_panel

# the clutch's modes as its columns hold them (clutch_mode)
OPEN = 3


def _headline(summary: dict) -> str | None:
    lockup, heat = float(summary["lockup_time"]), float(summary["slip_energy"]) / 1000
    if np.isnan(lockup):
        return f"clutch never locks ({heat:.2f} kJ of heat up to the end)"
    if lockup == 0 and float(summary.get("slip_duration", 0.0)) == 0:
        return "clutch never slips"
    events = summary.get("events")  # the run figure's: a clutch that locks again and again says how often
    locks = 0 if events is None else sum(1 for row in events if _text(row["kind"]) == "lock"
                                         and _text(row["element"]) == "clutch")
    if locks > 1:
        return f"clutch locks {locks} times (first at {lockup:.3f} s), {heat:.2f} kJ of heat"
    return f"clutch locks at {lockup:.3f} s, {heat:.2f} kJ of heat"


def _text(value) -> str:
    return value.decode() if isinstance(value, bytes) else str(value)


CONE_CLUTCH = Display(
    panels=(
        speed_panel(Trace("clutch output (pinion)", "pinion_speed", style="--", needs=("motor_speed", "slip_speed"),
                          value=lambda run: run["motor_speed"] - run["slip_speed"])),
        Panel("clutch_slip", "clutch slip [rpm]\n(motor - clutch output)", 10,
              (Trace("slip speed", "slip_speed", marks=("lock",), marks_of="clutch"),), scale=30.0 / np.pi,
              zero_line=True),
        Panel("clutch_torque", "clutch torque [N*m]", 20, (
            Trace("transmitted", "clutch_torque"),
            Trace("static capacity", "clutch_capacity", style=":", limit=True),
            # slipping backwards (a load running back), the torque meets the capacity's other side
            Trace("- static capacity", "clutch_capacity", style=":", limit=True,
                  needs=("clutch_capacity", "clutch_torque"),
                  value=lambda run: -run["clutch_capacity"] if (run["clutch_torque"] < 0).any() else None),
        ), zero_line=True),
    ),
    shading=(Phase("clutch open", "clutch_mode", OPEN, "0.3"), Phase("clutch locked", "clutch_locked", 1, "#1b7837")),
    summary_panels=(
        SummaryPanel("lockup_time", "lock-up time [s]", 0),
        SummaryPanel("slip_energy", "clutch heat [kJ]", 1, scale=1e-3, partial="heat up to the end of the run"),
        SummaryPanel("peak_clutch_torque", "peak clutch torque [N*m]", 2),
    ),
    outcomes=(
        Outcome("never locks", lambda row: np.isnan(row["lockup_time"]), "#b2182b", "^"),
        Outcome("never slips (locked from the start)",
                lambda row: row["lockup_time"] == 0 and row.get("slip_duration", 0.0) == 0, "#1b7837", "D"),
    ),
    headline=_headline,
    names_part="hoist",
)

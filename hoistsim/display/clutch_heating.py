"""The clutch's temperature (in degrees Celsius, against its limit) and whether a run overheats it."""

from __future__ import annotations

import numpy as np

from .panel import Display, Outcome, Panel, SummaryPanel, Trace

ZERO_CELSIUS = 273.15  # K: the figures speak degrees Celsius, the numbers kelvin


def _celsius(kelvin):
    return np.asarray(kelvin, dtype=float) - ZERO_CELSIUS


def _max_temperature(parameters: dict):
    """The scenario's max_temperature (K), None where it gives none (the hoist's clutch_heating, or the heating
    of a drawn clutch named clutch: the columns drawn here are its)."""
    drawn = ((parameters.get("drivetrain") or {}).get("clutches") or {}).get("clutch") or {}
    return (parameters.get("clutch_heating") or drawn.get("heating") or {}).get("max_temperature")


def _limit_line(run):
    """The max temperature across the run (degC), or None (not drawn) where the scenario gives none."""
    limit = _max_temperature(run["parameters"])
    return None if limit is None else np.full(np.shape(run["clutch_temperature"]), _celsius(limit))


def _headline(summary: dict) -> str | None:
    peak = f"clutch peaks at {_celsius(summary['peak_clutch_temperature']):.0f} degC"
    overheat = float(summary.get("overheat_time", np.nan))
    return peak if np.isnan(overheat) else f"{peak}, overheats at {overheat:.3f} s"


CLUTCH_HEATING = Display(
    panels=(Panel("clutch_temperature", "clutch temperature [degC]", 21, (
        Trace("friction surfaces", "clutch_temperature", value=lambda run: _celsius(run["clutch_temperature"]),
              marks=("overheat", "temperature_peak")),
        Trace("max temperature", "clutch_temperature", style=":", limit=True, value=_limit_line),
    )),),
    summary_panels=(SummaryPanel("peak_clutch_temperature", "peak clutch temperature [degC]", 3, offset=-ZERO_CELSIUS,
                                 limit=("max temperature", "clutch_heating.max_temperature")),),
    outcomes=(Outcome("overheats", lambda row: not np.isnan(row["overheat_time"]), "#e08214", "v"),),
    headline=_headline,
)

"""How a summary reads on the terminal, wherever a table shows it (``run``, ``compare``): its header (words, and
the unit it is shown in) and the scale from the SI value the file holds to the number shown.  One place, so that
a run's table and a file's comparison show the same summary alike; CSV and the file stay SI."""

from __future__ import annotations

import math

RPM = 30 / math.pi  # rad/s -> rpm


def _celsius(kelvin):
    return kelvin - 273.15


SUMMARY_COLUMNS = [  # (summary key, header, scale); a scale of None: a residual, unscaled, two digits
    ("lockup_time", "lock-up [s]", 1.0),
    ("slip_duration", "slipping [s]", 1.0),
    ("slip_energy", "clutch heat [kJ]", 1e-3),
    ("peak_clutch_torque", "peak torque [N*m]", 1.0),
    ("peak_slip_speed", "peak slip [rpm]", RPM),
    ("lowest_load_position", "lowest load [m]", 1.0),
    ("final_load_position", "final load [m]", 1.0),
    ("final_motor_speed", "final motor [rpm]", RPM),
    ("lock_events", "locks", 1),
    ("unlock_events", "unlocks", 1),
    ("energy_relative_residual", "relative energy residual", None),
]
# shown where the runs have them (a part the scene names): after the clutch's heat
OPTIONAL_COLUMNS = {"slip_energy": [("peak_clutch_temperature", "peak clutch [degC]", _celsius),
                                    ("overheat_time", "overheats [s]", 1.0)],
                    "final_load_position": [("lift_off_time", "lift-off [s]", 1.0),
                                            ("peak_rope_force", "peak rope [kN]", 1e-3),
                                            ("dynamic_factor", "phi", 1.0),
                                            ("dynamic_factor_standard", "phi2 EN 13001", 1.0),
                                            ("peak_buffer_force", "peak buffer [kN]", 1e-3),
                                            ("buffer_force_standard", "buffer EN 13001 [kN]", 1e-3)]}

PERIODIC_COLUMNS = [  # (summary key, header, scale): the motor shaft's periodic regime
    ("mean_speed", "mean speed [rpm]", RPM),
    ("max_speed", "max speed [rpm]", RPM),
    ("min_speed", "min speed [rpm]", RPM),
    ("irregularity", "delta", 1.0),
    ("irregularity_tredgold", "delta Tredgold", 1.0),
    ("energy_fluctuation", "dE_max [J]", 1.0),
    ("energy_fluctuation_tredgold", "dE_max Tredgold [J]", 1.0),
    ("settling_periods", "settled after [periods]", 1),
]

_KNOWN = {key: (header, scale) for key, header, scale in
          [*SUMMARY_COLUMNS, *(c for extra in OPTIONAL_COLUMNS.values() for c in extra), *PERIODIC_COLUMNS]}
# a drawn drivetrain's clutches, by name: suffix -> (header after the clutch's name, scale)
_PER_CLUTCH = {"_lockup_time": ("lock-up [s]", 1.0), "_slip_energy": ("heat [kJ]", 1e-3)}
# any other summary keeps its name; these SI units read as the tables' own do
_UNITS_SHOWN = {"rad/s": ("rpm", RPM), "K": ("degC", _celsius)}


def summary_header(key: str, unit: str = "") -> tuple[str, object]:
    """(header, scale) of the summary ``key`` held in SI ``unit``: the tables' own words where they have some
    (``lockup_time`` -> "lock-up [s]", ``clutch1_slip_energy`` -> "clutch1 heat [kJ]"), else the name with the
    unit it is shown in (speeds in rpm, temperatures in degC).  The scale multiplies, or is a function, or None
    (a residual)."""
    if key in _KNOWN:
        return _KNOWN[key]
    for suffix, (header, scale) in _PER_CLUTCH.items():
        if key.endswith(suffix):
            return f"{key[:-len(suffix)]} {header}", scale
    shown, scale = _UNITS_SHOWN.get(unit, (unit, 1.0))
    return (f"{key} [{shown}]" if shown and shown != "1" else key), scale


def scaled(value, scale):
    """A summary's SI value as shown with ``scale`` (:func:`summary_header`'s)."""
    if value is None:
        return None
    if callable(scale):
        return scale(value)
    return value * scale if scale not in (1, None) else value

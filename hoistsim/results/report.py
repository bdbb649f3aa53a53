"""Tables for the terminal: aligned columns, units in the headers."""

from __future__ import annotations

import math


def table(headers: list[str], rows: list[list[str]], align: str | None = None) -> str:
    """A plain-text table; ``align`` has one 'l' or 'r' per column (default: first left, rest right)."""
    align = align or "l" + "r" * (len(headers) - 1)
    widths = [max(len(str(x)) for x in col) for col in zip(headers, *rows)]

    def line(cells):
        return "  ".join(str(c).ljust(w) if a == "l" else str(c).rjust(w)
                         for c, w, a in zip(cells, widths, align)).rstrip()

    rule = "  ".join("-" * w for w in widths)
    return "\n".join([line(headers), rule, *(line(r) for r in rows)])


def fmt(value: float, digits: int = 4) -> str:
    if isinstance(value, bool):
        return "yes" if value else "no"
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, int):
        return str(value)
    if value != 0 and (abs(value) >= 1e5 or abs(value) < 1e-3):
        return f"{value:.{digits - 1}e}"
    return f"{value:.{digits}g}"


SUMMARY_COLUMNS = [  # (summary key, header, scale)
    ("lockup_time", "lock-up [s]", 1.0),
    ("slip_duration", "slipping [s]", 1.0),
    ("slip_energy", "clutch heat [kJ]", 1e-3),
    ("peak_clutch_torque", "peak torque [N*m]", 1.0),
    ("peak_slip_speed", "peak slip [rpm]", 30 / math.pi),
    ("lowest_load_position", "lowest load [m]", 1.0),
    ("final_load_position", "final load [m]", 1.0),
    ("final_motor_speed", "final motor [rpm]", 30 / math.pi),
    ("lock_events", "locks", 1),
    ("unlock_events", "unlocks", 1),
    ("energy_relative_residual", "energy residual", None),
]
# shown where the runs have them (a part the scene names): after the clutch's heat
OPTIONAL_COLUMNS = {"slip_energy": [("peak_clutch_temperature", "peak clutch [degC]", lambda kelvin: kelvin - 273.15),
                                    ("overheat_time", "overheats [s]", 1.0)],
                    "final_load_position": [("lift_off_time", "lift-off [s]", 1.0),
                                            ("peak_rope_force", "peak rope [kN]", 1e-3),
                                            ("dynamic_factor", "phi", 1.0),
                                            ("dynamic_factor_standard", "phi2 EN 13001", 1.0)]}


def summary_table(summaries: list[dict], head: int = 12, tail: int = 6) -> str:
    """Runs as rows, the summary as columns; long sweeps show their first and last runs."""
    first = summaries[0]
    columns = [(key, f"{key[:-len('_lockup_time')]} lock-up [s]", 1.0) for key in first
               if key.endswith("_lockup_time")]  # a drawn drivetrain's clutches, by name
    columns += [(key, f"{key[:-len('_slip_energy')]} heat [J]", 1.0) for key in first if key.endswith("_slip_energy")]
    for column in SUMMARY_COLUMNS:
        if column[0] in first:
            columns += [column] + [extra for extra in OPTIONAL_COLUMNS.get(column[0], ()) if extra[0] in first]

    def cell(value, scale):
        if scale is None:
            return f"{value:.1e}"
        return fmt(scale(value) if callable(scale) else value * scale if scale != 1 else value)

    shown = summaries if len(summaries) <= head + tail else summaries[:head] + [None] + summaries[-tail:]
    rows = [[s["label"]] + [cell(s[key], scale) for key, _, scale in columns] if s is not None
            else ["..."] + [""] * len(columns) for s in shown]
    text = table(["run"] + [header for _, header, _ in columns], rows)
    if len(summaries) > head + tail:
        text += f"\n({len(summaries)} runs; all of them: hoistsim compare OUT.h5 [--csv])"
    return text


PERIODIC_COLUMNS = [  # (summary key, header, scale)
    ("mean_speed", "mean [rpm]", 30 / math.pi),
    ("max_speed", "max [rpm]", 30 / math.pi),
    ("min_speed", "min [rpm]", 30 / math.pi),
    ("irregularity", "delta", 1.0),
    ("irregularity_tredgold", "delta Tredgold", 1.0),
    ("energy_fluctuation", "dE_max [J]", 1.0),
    ("energy_fluctuation_tredgold", "dE_max Tredgold [J]", 1.0),
    ("settling_periods", "settled after [periods]", 1),
]


def periodic_table(summaries: list[dict], head: int = 12, tail: int = 6) -> str:
    """The periodic regime of each run (motor shaft, analysed periods), Tredgold beside the simulation."""
    shown = summaries if len(summaries) <= head + tail else summaries[:head] + summaries[-tail:]
    rows = [[s["label"]] + [fmt(s[key] * scale if scale != 1 else s[key]) for key, _, scale in PERIODIC_COLUMNS]
            for s in shown]
    return table(["run"] + [header for _, header, _ in PERIODIC_COLUMNS], rows)


def flywheel_table(name: str, sizing, elapsed: float) -> str:
    """The flywheel command's answers, one per line."""
    motor = "at the motor shaft"
    on = f"on the {sizing.shaft} shaft"
    rows = [
        ["target delta", "degree of irregularity to meet", fmt(sizing.irregularity), "-"],
        ["w_m", "mean speed (mean over angle)", fmt(sizing.mean_speed * 30 / math.pi), "rpm"],
        ["dE_max", "largest energy fluctuation, Tredgold", fmt(sizing.energy_fluctuation), "J"],
        ["I_f,0", f"the scenario's own flywheel {on}", fmt(sizing.flywheel_as_given), "kg*m^2"],
        ["delta_0", "delta with it: simulated", fmt(sizing.irregularity_as_given), "-"],
        ["delta_0,T", "delta with it: Tredgold", fmt(sizing.irregularity_tredgold_as_given), "-"],
        ["I_machine", f"machine's own constant inertia {motor}", fmt(sizing.machine_inertia), "kg*m^2"],
        ["I_T", f"whole inertia Tredgold asks for {motor}", fmt(sizing.required_inertia_tredgold), "kg*m^2"],
        ["I_f,T", f"Tredgold's flywheel {on}", fmt(sizing.flywheel_inertia_tredgold), "kg*m^2"],
        ["delta(I_f,T)", "delta simulated with Tredgold's flywheel",
         fmt(sizing.irregularity_with_tredgold_flywheel, 6), "-"],
        ["I_f", f"flywheel with which the simulation meets the target, {on}", fmt(sizing.flywheel_inertia, 6),
         "kg*m^2"],
        ["delta(I_f)", "delta simulated with it (check)", fmt(sizing.irregularity_with_flywheel, 6), "-"],
    ]
    if sizing.rim is not None:
        r = sizing.rim
        rows += [["D_o", "rim outer diameter", fmt(r["outer_diameter"] * 1e3), "mm"],
                 ["D_i", "rim inner diameter", fmt(r["inner_diameter"] * 1e3), "mm"],
                 ["s", "rim width", fmt(r["width"] * 1e3), "mm"],
                 ["m", f"rim mass at {fmt(r['density'])} kg/m^3", fmt(r["mass"]), "kg"]]
    runs = len(sizing.candidates)
    return (f"{name}: flywheel for delta = {fmt(sizing.irregularity)} ({runs} runs simulated, {elapsed:.2f} s)\n"
            + table(["symbol", "quantity", "value", "unit"], rows, align="llrl"))


# What `compare` shows first: the questions a designer compares runs by.
COMPARE_FIRST = ["lockup_time", "slip_energy", "peak_clutch_torque", "lowest_load_position", "final_load_position",
                 "mean_speed", "irregularity", "irregularity_tredgold", "lock_events", "energy_relative_residual"]


def compare_table(rows: list[dict], units: dict[str, str], columns: list[str] | None = None,
                  width: int = 120) -> str:
    """The runs of a file as rows, chosen columns (names, then units, as headers), within ``width``.

    Without ``columns``: the label, the swept keys, then COMPARE_FIRST and the rest of the summary,
    as many as fit; a last line says how many were left out and how to see them.
    """
    names = list(rows[0])
    swept = [n for n in names if "." in n and n != "label"]  # swept keys (dotted) come before the summary
    chosen = columns or ["label", *swept, *[n for n in COMPARE_FIRST if n in names],
                         *[n for n in names if n not in COMPARE_FIRST and n not in swept and n != "label"]]
    unknown = [n for n in chosen if n not in names]
    if unknown:
        raise ValueError(f"no column {unknown[0]!r} in this file (columns: {', '.join(names)})")

    def cell(value):
        return value if isinstance(value, str) else fmt(value)

    shown, used = [], 0
    for name in chosen:
        cells = [name, units.get(name, ""), *(cell(r[name]) for r in rows)]
        need = max(len(c) for c in cells) + (2 if shown else 0)
        if columns is None and shown and used + need > width:
            break
        shown.append(name)
        used += need
    unit_row = [f"[{units[n]}]" if units.get(n) else "" for n in shown]
    names, rule, under, *body = table(shown, [unit_row] + [[cell(r[n]) for n in shown] for r in rows]).split("\n")
    text = "\n".join([names, under.rstrip(), rule, *body])  # the units under the names, above the rule
    left = len(chosen) - len(shown)
    if left:
        text += (f"\n({left} more column{'s' if left != 1 else ''}: --columns NAME,NAME,... to choose them, "
                 "--csv for all)")
    return text

"""Tables for the terminal: aligned columns, units in the headers, within the terminal's width (stacked blocks of
columns, or the columns that fit), and the same summaries as CSV."""

from __future__ import annotations

import math
from numbers import Real as numbers_Real

import numpy as np

from .summary_display import OPTIONAL_COLUMNS, PERIODIC_COLUMNS, SUMMARY_COLUMNS, scaled, summary_header
from .text_tables import column_layout, fitted_table, note, table


def csv_text(rows: list[dict], units: dict[str, str]) -> str:
    """Every run's summary as CSV: a header row, a units row, then the runs (SI)."""
    import csv
    import io

    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(list(rows[0]))
    writer.writerow([units.get(name, "") for name in rows[0]])
    writer.writerows([list(row.values()) for row in rows])
    return out.getvalue()


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


def column_cells(values: list, digits: int = 4) -> list[str]:
    """A column's values in one number format, so that they line up and read alike down the column: whole
    numbers as such (9000, 12000, never 9000 then 1.2e+04); else a fixed count of decimals giving the largest
    ``digits`` significant ones (0.350, 1.030); scientific for all where the largest is very large or very small,
    or where the column spans too many decades for decimals to show its smallest (a residual of 1e-10 beside
    1e-4).  Text stays as it is, a yes/no as such, a missing or NaN value "-"."""
    numbers = [float(v) for v in values if isinstance(v, numbers_Real) and not isinstance(v, bool)
               and math.isfinite(float(v))]
    sizes = [abs(x) for x in numbers if x != 0]
    if not sizes:
        form = "{:.0f}"
    elif all(x == round(x) for x in numbers) and max(sizes) < 1e7:
        form = "{:.0f}"
    elif max(sizes) >= 1e5 or max(sizes) < 1e-3 or (min(sizes) < 1e-3 and max(sizes) / min(sizes) >= 1e4):
        form = f"{{:.{digits - 1}e}}"
    else:
        form = f"{{:.{min(max(digits - 1 - math.floor(math.log10(max(sizes))), 0), 6)}f}}"

    def cell(value) -> str:
        if isinstance(value, str):
            return value
        if isinstance(value, bool):
            return "yes" if value else "no"
        if value is None or isinstance(value, numbers_Real) and math.isnan(float(value)):
            return "-"
        if not isinstance(value, numbers_Real) or math.isinf(float(value)):
            return str(value)
        return form.format(float(value))

    return [cell(v) for v in values]


def summary_table(summaries: list[dict], head: int = 12, tail: int = 6, width: int | None = None) -> str:
    """Runs as rows, the summary as columns, in blocks within ``width`` (None: one block); long sweeps show their
    first and last runs."""
    first = summaries[0]
    keys = [key for key in first if key.endswith("_lockup_time")]  # a drawn drivetrain's clutches, by name
    keys += [key for key in first if key.endswith("_slip_energy")]
    for key, _, _ in SUMMARY_COLUMNS:
        if key in first:
            keys += [key] + [extra for extra, _, _ in OPTIONAL_COLUMNS.get(key, ()) if extra in first]
    shown = summaries if len(summaries) <= head + tail else summaries[:head] + [None] + summaries[-tail:]
    kept = [s for s in shown if s is not None]
    headers, cells = zip(*(summary_cells(key, [s[key] for s in kept]) for key in keys)) if keys else ((), ())
    by_run = iter(zip(*cells)) if cells else iter([[]] * len(kept))
    rows = [[s["label"], *next(by_run)] if s is not None else ["..."] + [""] * len(keys) for s in shown]
    text = fitted_table(["run", *headers], rows, width)
    if len(summaries) > head + tail:
        text += f"\n({len(summaries)} runs; all of them: hoistsim compare OUT.h5 [--csv])"
    return text


def summary_cells(key: str, values: list, unit: str = "") -> tuple[str, list[str]]:
    """The summary ``key``'s header and its values (SI, in ``unit``) as every table of summaries shows them: the
    words, unit and scale of :func:`hoistsim.results.summary_display.summary_header`, one number format down the
    column."""
    header, scale = summary_header(key, unit)
    return header, column_cells([scaled(value, scale) for value in values], digits=2 if scale is None else 4)


def periodic_table(summaries: list[dict], head: int = 12, tail: int = 6, width: int | None = None) -> str:
    """The periodic regime of each run (motor shaft, analysed periods), Tredgold beside the simulation, in blocks
    within ``width`` (None: one block)."""
    shown = summaries if len(summaries) <= head + tail else summaries[:head] + summaries[-tail:]
    rows = [[s["label"]] + [fmt(s[key] * scale if scale != 1 else s[key]) for key, _, scale in PERIODIC_COLUMNS]
            for s in shown]
    return fitted_table(["run"] + [header for _, header, _ in PERIODIC_COLUMNS], rows, width)


def flywheel_table(name: str, sizing, elapsed: float, width: int | None = None) -> str:
    """The flywheel command's answers, one per line, within ``width`` characters (None: however wide)."""
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
    return (note(f"{name}: flywheel for delta = {fmt(sizing.irregularity)} ({runs} runs simulated, {elapsed:.2f} s)",
                 width) + "\n" + table(["symbol", "quantity", "value", "unit"], rows, align="llrl", width=width))


# What `compare` shows first: the questions a designer compares runs by (when the clutch locks, its heat, where
# the load went), then the rest.
COMPARE_FIRST = ["lockup_time", "slip_energy", "lowest_load_position", "final_load_position", "peak_clutch_torque",
                 "peak_rope_force", "mean_speed", "irregularity", "irregularity_tredgold", "lock_events",
                 "energy_relative_residual"]


def compare_table(rows: list[dict], units: dict[str, str], columns: list[str] | None = None,
                  width: int | None = 120) -> str:
    """The runs of a file as rows, chosen columns (each summary headed, scaled and formatted as the run's table
    shows it, :func:`summary_cells`; units under the names), within ``width``.

    Without ``columns``: the run (its label, or within a ``width`` the swept keys' values where the labels only
    say them), then
    COMPARE_FIRST and the rest of the summary, as many as fit; a last line says how many were left out and how
    to see them.  With ``columns``: those, in stacked blocks within ``width``.  ``width`` None: every column,
    one block however wide.
    """
    names = list(rows[0])
    swept = [n for n in names if "." in n and n != "label"]  # swept keys (dotted) come before the summary
    # a sweep's labels repeat its keys' values ("clutch.engagement_force=3 kN"): the values alone, narrower
    said = width is not None and bool(swept) and all(f"{key}=" in str(r["label"]) for r in rows for key in swept)
    run = swept if said else ["label", *swept]
    chosen = columns or [*run, *[n for n in COMPARE_FIRST if n in names],
                         *[n for n in names if n not in COMPARE_FIRST and n not in run and n != "label"]]
    unknown = [n for n in chosen if n not in names]
    if unknown:
        raise ValueError(f"no column {unknown[0]!r} in this file (columns: {', '.join(names)})")

    headers, columns_shown = zip(*(_compare_cells(n, [r[n] for r in rows], units.get(n, "")) for n in chosen))
    cells = [list(run) for run in zip(*columns_shown)]
    count = len(chosen)
    if columns is None and width is not None:  # as many as fit beside the label, as fitted_table lays them out
        widths = column_layout(headers, cells)[2]
        count = max(1, sum(1 for i in range(len(chosen)) if sum(widths[:i + 1]) + 2 * i <= width))
    shown = chosen[:count]
    keep = min(len(run) if columns is None else 1, count)  # what names the run, repeated in each block
    text = fitted_table(headers[:count], [row[:count] for row in cells], width,
                        align="".join("l" if name == "label" else "r" for name in shown), keep=keep)
    left = len(chosen) - len(shown)
    if left:
        text += "\n" + note(f"({left} more column{'s' if left != 1 else ''}: --wide or --csv for all, "
                            "--columns A,B,... to choose)", width)
    return text


def _compare_cells(name: str, values: list, unit: str) -> tuple[str, list[str]]:
    """A file's column as ``compare`` shows it: a summary as the run's table does (:func:`summary_cells`), the
    label as "run", a swept key by its dotted name in SI."""
    if name == "label":
        return "run", column_cells(values)
    if "." in name:
        return (f"{name} [{unit}]" if unit and unit != "1" else name), column_cells(values)
    return summary_cells(name, values, unit)


def sensitivity_table(result, width: int | None = None) -> str:
    """A :class:`hoistsim.results.sensitivity_result.Sensitivity` as two tables, a row a summary: each derivative with
    its units, then the elasticities (dimensionless: comparable across keys); within ``width`` characters as
    :func:`fitted_table` stacks them."""
    keys = list(result.keys)
    lines = _key_values(result.keys, result.key_units, width)
    headers = ["summary", "value"] + [f"d/d {key}" for key in keys]
    derivatives, elasticities = [], []
    for name, value in result.values.items():
        units = "" if result.units[name] == "1" else f" {result.units[name]}"
        cells = [f"{fmt(result.derivatives[name][key], 5)} {result.derivative_units(name, key)}"
                 if result.derivatives[name][key] == result.derivatives[name][key] else "-" for key in keys]
        derivatives.append([name, fmt(value, 6) + units, *cells])
        elasticities.append([name, *(fmt(result.elasticity(name, key), 3) for key in keys)])
    return "\n".join([
        note(f"{result.name}: how each summary moves with each key,", width),
        *lines,
        *(note(f"({key} is a table: its number is its largest force, every force scaled with it)", width)
          for key in result.tables),
        note("(derivatives exact through every switch; '-': none, the summary itself is none)", width), "",
        fitted_table(headers, derivatives, width), "",
        note("elasticity = key / summary x derivative: the summary's relative change per relative change of the "
             "key", width),
        "", fitted_table(["summary", *keys], elasticities, width)])


def _key_values(values: dict, units: dict, width: int | None) -> list[str]:
    """"at key = value unit, ..." within ``width``, a key and its value kept on one line."""
    at = [f"{key} = {fmt(value, 6)}" + ("" if units[key] == "1" else f" {units[key]}") for key, value in values.items()]
    lines = ["at"]
    for k, item in enumerate(at):
        item += "," if k < len(at) - 1 else ""
        if len(lines[-1]) + 1 + len(item) > (width or 100):
            lines.append("  ")
        lines[-1] += " " + item
    return lines


def sweep_sensitivity_table(result, width: int | None = None, head: int = 12, tail: int = 6) -> str:
    """A :class:`hoistsim.running.sweep_sensitivity.SweepSensitivity` as a table a summary: the runs as rows, the
    summary's value, its derivative with respect to each key (units in the headers) and the elasticities; long
    sweeps show their first and last runs."""
    count = len(result)
    rows = list(range(count)) if count <= head + tail else [*range(head), None, *range(count - tail, count)]
    shown = [i for i in rows if i is not None]
    held = {key: float(v[0]) for key, v in result.wrt.items() if key not in result.keys and np.all(v == v[0])}
    texts = [note(f"{result.scenario.name}, {count} runs: how each summary moves with each key"
                  + ("," if held else ""), width),
             *(_key_values(held, result.key_units, width) if held else []),
             *(note(f"({key} is a table: its number is its largest force, every force scaled with it)", width)
               for key in result.tables),
             note("(derivatives exact through every switch; '-': none, the summary itself is none; "
                  "elasticity = key / summary x derivative)", width)]
    for name, values in result.values.items():
        units = "" if result.units[name] == "1" else f" [{result.units[name]}]"
        headers = ["run", f"{name}{units}",
                   *(f"d/d {key} [{result.derivative_units(name, key)}]" for key in result.wrt),
                   *(f"elasticity {key}" for key in result.wrt)]
        columns = [column_cells([float(values[i]) for i in shown], 6),
                   *(column_cells([float(result.derivatives[name][key][i]) for i in shown], 5) for key in result.wrt),
                   *(column_cells([float(result.elasticity(name, key)[i]) for i in shown], 3) for key in result.wrt)]
        cells = iter(zip(*columns))
        table_rows = [[result.labels[i], *next(cells)] if i is not None else ["..."] + [""] * len(columns)
                      for i in rows]
        texts += ["", fitted_table(headers, table_rows, width)]
    return "\n".join(texts)

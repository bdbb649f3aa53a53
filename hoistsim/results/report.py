"""Tables for the terminal: aligned columns, units in the headers, within the terminal's width (stacked blocks of
columns, or the columns that fit), and the same summaries as CSV."""

from __future__ import annotations

import math
import re
from numbers import Real as numbers_Real

import numpy as np


def table(headers: list[str], rows: list[list[str]], align: str | None = None) -> str:
    """A plain-text table; ``align`` has one 'l' or 'r' per column (default: first left, rest right)."""
    align = align or "l" + "r" * (len(headers) - 1)
    widths = [max(len(str(x)) for x in col) for col in zip(headers, *rows)]

    def line(cells):
        return "  ".join(str(c).ljust(w) if a == "l" else str(c).rjust(w)
                         for c, w, a in zip(cells, widths, align)).rstrip()

    rule = "  ".join("-" * w for w in widths)
    return "\n".join([line(headers), rule, *(line(r) for r in rows)])


def fitted_table(headers: list[str], rows: list[list[str]], width: int | None = None, align: str | None = None,
                 keep: int = 1) -> str:
    """A table within ``width`` characters: each header "name [unit]" with its unit on a line of its own under the
    name, the name wrapped (:func:`_wrap`) where its column's values are narrower than it; the columns in blocks
    stacked one under the other, each block repeating the first ``keep`` columns (the row's label) and as many
    of the others as fit.  ``width`` None: one block however wide, the names unwrapped.  ``align`` as for
    :func:`table` (default: the kept columns left, the rest right)."""
    align = align or "l" * keep + "r" * (len(headers) - keep)
    name_lines, units, widths = _columns(headers, rows, wrap=width is not None)
    blocks = _blocks(widths, keep, width)
    if len(blocks) > 1:  # as few blocks, evened out: the narrowest width that needs no more of them
        blocks = next((b for limit in range(sum(widths[:keep]), width + 1)
                       if len(b := _blocks(widths, keep, limit)) == len(blocks)), blocks)

    def line(cells, shown):
        return "  ".join(str(cells[i]).ljust(widths[i]) if align[i] == "l" else str(cells[i]).rjust(widths[i])
                         for i in shown).rstrip()

    texts = []
    for block in blocks:
        shown = [*range(keep), *block]
        tall = max(len(name_lines[i]) for i in shown)
        # the names' lines sit on the unit's line: a shorter name is padded above
        head = [line([([""] * (tall - len(lines)) + lines)[k] for lines in name_lines], shown) for k in range(tall)]
        head += [line(units, shown)] if any(units[i] for i in shown) else []
        texts.append("\n".join([*head, "  ".join("-" * widths[i] for i in shown), *(line(r, shown) for r in rows)]))
    return "\n\n".join(texts)


def _columns(headers: list[str], rows: list[list[str]], wrap: bool = True):
    """Each column's name as lines (wrapped to its values' width unless not ``wrap``), its unit, its width."""
    names, units = zip(*(_name_and_unit(h) for h in headers))
    widths = [max(len(str(x)) for x in col) for col in zip(units, *rows)]
    name_lines = [_wrap(name, w) if wrap else [name] for name, w in zip(names, widths)]
    return name_lines, units, [max(w, *(len(line) for line in lines)) for w, lines in zip(widths, name_lines)]


def _wrap(name: str, width: int) -> list[str]:
    """A column's name on lines of at most ``width`` where it can be: broken after a space, an underscore or a dot
    (a summary's key, ``peak_clutch_`` over ``torque``), never inside a word."""
    lines = [""]
    for piece in re.split(r"(?<=[ _.])", name):
        if lines[-1] and len((lines[-1] + piece).rstrip()) > width:
            lines.append("")
        lines[-1] += piece
    return [line.rstrip() for line in lines]


def _blocks(widths: list[int], keep: int, width: int | None) -> list[list[int]]:
    """The columns after the first ``keep``, in order, as many to a block as fit ``width`` beside those."""
    blocks, block, used = [], [], sum(widths[:keep]) + 2 * (keep - 1)
    for i in range(keep, len(widths)):
        if block and width is not None and used + 2 + widths[i] > width:
            blocks.append(block)
            block, used = [], sum(widths[:keep]) + 2 * (keep - 1)
        block.append(i)
        used += 2 + widths[i]
    return [*blocks, block]


def _name_and_unit(header: str) -> tuple[str, str]:
    """"peak torque [N*m]" -> ("peak torque", "[N*m]"); a header without a unit keeps an empty one."""
    name, bracket, unit = header.partition(" [")
    return (name, f"[{unit}") if bracket and unit.endswith("]") else (header, "")


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


def summary_table(summaries: list[dict], head: int = 12, tail: int = 6, width: int | None = None) -> str:
    """Runs as rows, the summary as columns, in blocks within ``width`` (None: one block); long sweeps show their
    first and last runs."""
    first = summaries[0]
    columns = [(key, f"{key[:-len('_lockup_time')]} lock-up [s]", 1.0) for key in first
               if key.endswith("_lockup_time")]  # a drawn drivetrain's clutches, by name
    columns += [(key, f"{key[:-len('_slip_energy')]} heat [J]", 1.0) for key in first if key.endswith("_slip_energy")]
    for column in SUMMARY_COLUMNS:
        if column[0] in first:
            columns += [column] + [extra for extra in OPTIONAL_COLUMNS.get(column[0], ()) if extra[0] in first]

    def scaled(value, scale):
        return scale(value) if callable(scale) else value * scale if scale not in (1, None) else value

    shown = summaries if len(summaries) <= head + tail else summaries[:head] + [None] + summaries[-tail:]
    kept = [s for s in shown if s is not None]
    cells = [column_cells([scaled(s[key], scale) for s in kept], digits=2 if scale is None else 4)
             for key, _, scale in columns]
    by_run = iter(zip(*cells)) if cells else iter([[]] * len(kept))
    rows = [[s["label"], *next(by_run)] if s is not None else ["..."] + [""] * len(columns) for s in shown]
    text = fitted_table(["run"] + [header for _, header, _ in columns], rows, width)
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


def periodic_table(summaries: list[dict], head: int = 12, tail: int = 6, width: int | None = None) -> str:
    """The periodic regime of each run (motor shaft, analysed periods), Tredgold beside the simulation, in blocks
    within ``width`` (None: one block)."""
    shown = summaries if len(summaries) <= head + tail else summaries[:head] + summaries[-tail:]
    rows = [[s["label"]] + [fmt(s[key] * scale if scale != 1 else s[key]) for key, _, scale in PERIODIC_COLUMNS]
            for s in shown]
    return fitted_table(["run"] + [header for _, header, _ in PERIODIC_COLUMNS], rows, width)


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


# What `compare` shows first: the questions a designer compares runs by (when the clutch locks, its heat, where
# the load went), then the rest.
COMPARE_FIRST = ["lockup_time", "slip_energy", "lowest_load_position", "final_load_position", "peak_clutch_torque",
                 "peak_rope_force", "mean_speed", "irregularity", "irregularity_tredgold", "lock_events",
                 "energy_relative_residual"]


def compare_table(rows: list[dict], units: dict[str, str], columns: list[str] | None = None,
                  width: int | None = 120) -> str:
    """The runs of a file as rows, chosen columns (names, then units, as headers), within ``width``.

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

    headers = [f"{n} [{units[n]}]" if units.get(n) else n for n in chosen]
    cells = [list(run) for run in zip(*(column_cells([r[n] for r in rows]) for n in chosen))]
    count = len(chosen)
    if columns is None and width is not None:  # as many as fit beside the label, as fitted_table lays them out
        widths = _columns(headers, cells)[2]
        count = max(1, sum(1 for i in range(len(chosen)) if sum(widths[:i + 1]) + 2 * i <= width))
    shown = chosen[:count]
    keep = min(len(run) if columns is None else 1, count)  # what names the run, repeated in each block
    text = fitted_table(headers[:count], [row[:count] for row in cells], width,
                        align="".join("l" if name == "label" else "r" for name in shown), keep=keep)
    left = len(chosen) - len(shown)
    if left:
        text += (f"\n({left} more column{'s' if left != 1 else ''}: --wide or --csv for all, "
                 "--columns A,B,... to choose)")
    return text


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
        f"{result.name}: how each summary moves with each key,",
        *lines,
        *(f"({key} is a table: its number is its largest force, every force scaled with it)"
          for key in result.tables),
        "(derivatives exact through every switch; '-': none, the summary itself is none)", "",
        fitted_table(headers, derivatives, width), "",
        "elasticity = key / summary x derivative: the summary's relative change per relative change of the key",
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
    texts = [f"{result.scenario.name}, {count} runs: how each summary moves with each key" + ("," if held else ""),
             *(_key_values(held, result.key_units, width) if held else []),
             *(f"({key} is a table: its number is its largest force, every force scaled with it)"
               for key in result.tables),
             "(derivatives exact through every switch; '-': none, the summary itself is none;",
             " elasticity = key / summary x derivative)"]
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


def fit_table(name: str, result) -> str:
    """A :class:`hoistsim.studies.fit.FitResult` as tables: each key's start, fitted value, standard error
    and 95 % interval in its units; each matched series' residual RMS in the trace's unit."""
    keys = [[key, fmt(result.start[key], 6), fmt(result.values[key], 6), fmt(result.standard_errors[key], 3),
             f"{fmt(result.intervals[key][0], 6)} to {fmt(result.intervals[key][1], 6)}",
             "" if result.key_units[key] == "1" else result.key_units[key]] for key in result.keys]
    trace = result.trace
    rms = [[column, fmt(float(trace.shown(column, result.residual_rms[column]) - trace.shown(column, 0.0)), 4),
            trace.written[column]] for column in result.residual_rms]
    state = (f"converged in {result.iterations} iterations" if result.converged
             else f"not converged after {result.iterations} iterations")
    return "\n".join([
        f"{name}: fitted to {trace.source} ({trace.time.size} times from {trace.time[0]:g} to {trace.time[-1]:g} s; "
        f"{state})", "",
        table(["key", "start", "fitted", "std error", "95 % interval", "unit"], keys, align="lrrrrl"), "",
        table(["series", "residual RMS", "unit"], rms, align="lrl")])


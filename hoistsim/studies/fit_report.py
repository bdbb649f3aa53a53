"""A fit as the terminal shows it, within its width: what was fitted to which trace, each key's value and
interval, each series' residual RMS beside the noise."""

from __future__ import annotations

from ..results.report import fmt
from ..results.text_tables import note, table


def fit_report(name: str, result, width: int | None = None) -> str:
    """A :class:`hoistsim.studies.fit.FitResult` as text within ``width`` characters (None: however wide):
    each key's value in the scenario, where the fit started, the fitted value, its standard error and 95 %
    interval ('-' and "undetermined" where the trace does not determine it); each matched series' residual RMS
    and the noise estimated from its residuals, in the trace's unit.  The warnings are the caller's to show."""
    trace = result.trace
    if result.sound:
        state = f"converged in {result.iterations} iterations"
    else:
        count = len(result.warnings)
        state = f"{result.iterations} iterations, {count} warning{'s' if count > 1 else ''}: not a sound fit"
    lines = [note(f"{name}: fitted to {trace.source} ({trace.time.size} times from {trace.time[0]:g} to "
                  f"{trace.time[-1]:g} s; {state})", width)]
    swept = result.swept
    if swept is not None:
        where = "the best of them" if swept.moved else "the scenario's values: none of them did better"
        ranges = ", ".join(f"{key} {_amounts(result, key, lo, hi)}" for key, (lo, hi) in swept.ranges.items())
        given = _amounts(result, None, *result.given.values(), joined=", ")
        lines.append(note(f"{swept.count} starting points swept over {ranges} (the scenario's: {given}); the fit "
                          f"started from {where}", width))
    lines += ["", _keys_table(result, width), "", _residuals_table(result, width)]
    return "\n".join(lines)


def _amounts(result, key: str | None, *values: float, joined: str = " to ") -> str:
    """Values of ``key`` (None: one of each fitted key, in order) with their units, 4 digits."""
    keys = [key] * len(values) if key is not None else result.keys
    texts = [fmt(v, 4) + ("" if result.key_units[k] == "1" else f" {result.key_units[k]}")
             for k, v in zip(keys, values)]
    if key is not None and result.key_units[key] != "1":  # a range says its unit once
        texts = [fmt(v, 4) for v in values[:-1]] + texts[-1:]
    return joined.join(texts)


def _keys_table(result, width: int | None) -> str:
    headers = ["key", "start", "fitted", "std error", "95 % low", "95 % high"]
    rows = []
    for key in result.keys:
        interval = result.intervals[key]
        error = result.standard_errors[key]
        unit = "" if result.key_units[key] == "1" else f" [{result.key_units[key]}]"
        ends = ["undetermined", ""] if interval is None else [fmt(interval[0], 6), fmt(interval[1], 6)]
        rows.append([key + unit, fmt(result.start[key], 4), fmt(result.values[key], 6),
                     "-" if error is None else fmt(error, 3), *ends])
    text = table(headers, rows, align="lrrrrr", width=width)
    if width is None or max(len(line) for line in text.splitlines()) <= width:
        return text
    # a key's name too long for a row within the width: each key a paragraph of its own
    # (no line broken inside "95 %": a no-break space holds it together until the lines are made)
    return "\n".join(note(f"{name}: start {start}, fitted {fitted}, std error {error}, "
                           + ("undetermined" if not high else f"95\xa0% interval {low} to {high}"),
                           width).replace("\xa0", " ")
                      for name, start, fitted, error, low, high in rows)


def _residuals_table(result, width: int | None) -> str:
    trace = result.trace
    rows = []
    for name, check in result.checks.items():
        rows.append([name, fmt(_amount(trace, name, check.rms), 4), fmt(_amount(trace, name, check.noise), 4),
                     trace.written[name]])
    return table(["series", "residual RMS", "noise", "unit"], rows, align="lrrl", width=width)


def _amount(trace, name: str, value: float) -> float:
    """A difference of a series in SI, in the unit the trace writes it in."""
    return float(trace.shown(name, value) - trace.shown(name, 0.0))

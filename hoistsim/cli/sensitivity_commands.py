"""`hoistsim sensitivity` and `fit`: how far each summary moves with each key (derivatives through every
switch), and the keys that explain a trace measured on a rig."""

from __future__ import annotations

import click

from .group import RUN_FAILED, debug_option, fail, main, one_line_errors, read_scenario, strict_option
from .terminal import compiling, table_width


def _names(text: str | None) -> list[str] | None:
    return None if text is None else [name.strip() for name in text.split(",") if name.strip()]


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("--wrt", required=True, metavar="KEY,KEY,...",
              help="The scenario keys to differentiate with respect to, each holding a number, e.g. "
                   "clutch.static_friction,clutch.kinetic_friction,load.mass.")
@click.option("--of", "of", metavar="SUMMARY,...",
              help="The summaries to differentiate (default: every summary that is a number), e.g. "
                   "lockup_time,slip_energy.")
@click.option("--json", "as_json", is_flag=True,
              help="Print the values, derivatives (SI) and elasticities as a JSON object.")
@click.option("--series", is_flag=True,
              help="Also write the run's results file (-o) with each series' derivative with respect to each key as "
                   "a series of its own, d_<series>_d_<key>.")
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False), metavar="OUT.h5",
              help="The results file --series writes (replaced atomically); of a sweep, its summary-only file with "
                   "each run's derivatives as summary columns, d_<summary>_d_<key>.")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@click.option("--sweep", "sweeps", multiple=True, metavar="KEY=V1,V2,..|KEY=FROM:TO:COUNT",
              help="Sweep a key (replacing the scenario's sweep of it): every run differentiated at its own values.")
@strict_option
@debug_option
@one_line_errors
def sensitivity(scenario, wrt, of, as_json, series, output, overrides, sweeps):
    """How far each summary of SCENARIO moves with each key: its derivative, exact through every switch,
    and its elasticity (key / summary x derivative: the summary's relative change per relative change of
    the key).  A summary that does not exist (a lock-up that never comes) has none: '-'.  A scenario with a
    sweep: every run's, each at its own values."""
    import json

    from .. import _jax
    from ..results.report import sensitivity_table, sweep_sensitivity_table
    from ..running.sensitivity import sensitivity as differentiate

    scenario = read_scenario(scenario, overrides, sweeps)
    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    from ..running.simulation import SimulationError

    from .group import RESULT_SUFFIXES

    swept = bool(scenario.sweep)
    if series and output is None:
        fail("--series writes the run's results file: name it with -o OUT.h5")
    if output is not None and not series and not swept:
        fail("-o names the results file --series writes: add --series")
    if output is not None and not output.lower().endswith(RESULT_SUFFIXES):
        fail(f"{output}: the results file must be named .h5, .hdf5 or .nc")
    command = " ".join(["hoistsim sensitivity", str(scenario.provenance.source), "--wrt", wrt,
                        *(["--of", of] if of else []), *(["--series"] if series else []), "-o", str(output),
                        *(f"--set {o}" for o in overrides), *(f"--sweep {w}" for w in sweeps)])
    try:
        result = differentiate(scenario, _names(wrt), _names(of), series=series)
        if series:
            from ..results.output import write_runs

            write_runs(output, [result.run], command=command)
        elif output is not None:
            result.to_hdf5(output, command=command)
    except SimulationError as exc:  # a run that cannot be completed (a chattering clutch): exit 1
        fail(str(exc), RUN_FAILED)
    if as_json:
        click.echo(json.dumps(result.to_dict(), indent=2))
    elif swept:
        click.echo(sweep_sensitivity_table(result, table_width()))
    else:
        click.echo(sensitivity_table(result, table_width()))
    if output is not None:
        what = "each series' derivatives: d_<series>_d_<key>" if series else \
            "each run's summaries and derivatives: d_<summary>_d_<key>"
        click.echo(f"wrote {output} ({what})", err=as_json)


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("--measured", required=True, type=click.Path(dir_okay=False), metavar="TRACE.csv",
              help="The measured trace: a CSV whose header names a 'time [s]' column and the matched series as "
                   "the results file does, units in brackets ('motor_speed [rpm]').")
@click.option("--match", required=True, metavar="SERIES,...", help="The series to match, e.g. motor_speed,drum_speed.")
@click.option("--fit", "keys", required=True, metavar="KEY,...",
              help="The scenario keys to fit, each holding a number, e.g. "
                   "clutch.static_friction,clutch.kinetic_friction; they start from the best of --starts points swept "
                   "over their ranges, or the scenario's values where none is better.")
@click.option("--bounds", multiple=True, metavar="KEY=LO:HI",
              help='Hold a fitted key within LO and HI, e.g. --bounds "clutch.kinetic_friction=0.05:0.2". Repeatable.')
@click.option("--range", "ranges", multiple=True, metavar="KEY=LO:HI",
              help='Where to look for a fitted key before the fit starts, e.g. --range "load.mass=50 kg:2 t" '
                   "(repeatable, or comma separated); default: its --bounds, else what a real part's value lies "
                   "in, else a third to three times the scenario's value.")
@click.option("--starts", type=click.IntRange(min=0), default=256, show_default=True, metavar="COUNT",
              help="Starting points swept over the keys' ranges, all in one compiled call; the fit starts from "
                   "the one whose run meets the trace best (0: from the scenario's values).")
@click.option("-o", "--output", type=click.Path(dir_okay=False), metavar="FITTED.yaml",
              help="Also write the scenario with the fitted values, atomically: only the fitted keys' lines "
                   "change, each commented with the trace, the fit's RMS and the key's interval.")
@click.option("--plot", "figure", type=click.Path(dir_okay=False), metavar="FIG.png",
              help="Also draw each matched series measured against fitted, with the residual (.png, .svg, .pdf).")
@click.option("--json", "as_json", is_flag=True,
              help="Print the fitted values, errors, intervals, residual checks and warnings as JSON (SI).")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@strict_option
@debug_option
@one_line_errors
def fit(scenario, measured, match, keys, bounds, ranges, starts, output, figure, as_json, overrides):
    """Fit keys of SCENARIO to a trace measured on a rig: the keys' ranges swept first, then least squares
    of the run's series against the measured columns at the measured times (Levenberg-Marquardt with the
    exact Jacobian, through every switch), each key with its standard error and 95 % interval; a key the
    trace does not determine, or residuals far from the noise or patterned, are warned of; -o writes the
    fitted scenario."""
    import json
    from pathlib import Path

    from .. import _jax
    from ..results.atomic import atomic_path
    from ..running.simulation import SimulationError
    from ..studies.fit import fit as fit_keys
    from ..studies.fit import parse_ranges
    from ..studies.fit_report import fit_report
    from ..studies.fitted_yaml import fitted_text

    if figure is not None and Path(figure).suffix.lower() not in (".png", ".svg", ".pdf"):
        fail(f"{figure}: the figure must be .png, .svg or .pdf")
    if output is not None and Path(output).suffix.lower() not in (".yaml", ".yml"):
        fail(f"{output}: the fitted scenario is written as YAML: name it .yaml")
    scenario = read_scenario(scenario, overrides)
    limits = parse_ranges(list(bounds), "--bounds")
    spans = parse_ranges(list(ranges), "--range")
    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    try:
        result = fit_keys(scenario, measured, _names(match), _names(keys), limits, spans, starts)
    except SimulationError as exc:
        fail(str(exc), RUN_FAILED)
    if output is not None:
        text = fitted_text(result)
        with atomic_path(output) as path:
            path.write_text(text, encoding="utf-8")
    if figure is not None:
        from ..figures.fit import fit_figure

        with atomic_path(figure) as path:
            fit_figure(result, path, title=scenario.name, kind=Path(figure).suffix[1:].lower())
    if as_json:
        click.echo(json.dumps(result.to_dict(), indent=2))
    else:
        click.echo(fit_report(scenario.name, result, table_width()))
    for warning in result.warnings:
        click.echo(f"hoistsim: warning: {warning}", err=True)
    written = [name for name in (output, figure) if name is not None]
    if written:
        click.echo(f"wrote {' and '.join(written)}", err=as_json)

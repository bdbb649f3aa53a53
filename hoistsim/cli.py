"""The `hoistsim` command line.

Exit status: 0 success, 1 a run that could not be completed (chattering, solver
failure), 2 bad input (scenario, options, files).  Errors are one line on
stderr; --debug shows the traceback.
"""

from __future__ import annotations

import functools
import os
import sys
import time
from pathlib import Path

# Before equinox is imported: its runtime checks become NaNs rather than host
# callbacks, so compiled runs can be kept in the persistent cache.  A library
# user's own equinox code is left as it is; only the command line sets this.
os.environ.setdefault("EQX_ON_ERROR", "nan")

import click  # noqa: E402

from .errors import ScenarioError  # noqa: E402
from .terminal import compiling, progress_printer  # noqa: E402

BAD_INPUT, RUN_FAILED = 2, 1


class _Failure(Exception):
    def __init__(self, message: str, status: int):
        super().__init__(message)
        self.status = status


# Names a results file may take: what HDF5 and netCDF-4 readers (h5py, xarray) expect.
RESULT_SUFFIXES = (".h5", ".hdf5", ".nc")


def _scenario(path, overrides=(), sweeps=()):
    """Load and validate a scenario; what it accepted but may not mean is said on stderr, one line each."""
    from .scenario import load_scenario

    scenario = load_scenario(path, overrides=list(overrides), sweeps=list(sweeps))
    for warning in scenario.warnings:
        click.echo(f"hoistsim: warning: {warning}", err=True)
    return scenario


def _fail(message: str, status: int = BAD_INPUT):
    raise _Failure(message, status)


def _guarded(func):
    """Turn known failures into one line on stderr and an exit status (``--debug``: raise)."""

    @functools.wraps(func)
    def wrapper(*, debug: bool = False, **kwargs):
        try:
            return func(**kwargs)
        except _Failure as exc:
            if debug:
                raise
            click.echo(f"hoistsim: error: {exc}", err=True)
            sys.exit(exc.status)
        except ScenarioError as exc:
            if debug:
                raise
            click.echo(f"hoistsim: error: {exc}", err=True)
            sys.exit(BAD_INPUT)
        except KeyboardInterrupt:
            click.echo("hoistsim: interrupted; nothing was written", err=True)
            sys.exit(130)
        except BrokenPipeError:  # output piped into `head` and the like: stop quietly
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            sys.exit(1)
        except Exception as exc:  # an internal error: still one line unless --debug
            if debug:
                raise
            text = str(exc).strip().splitlines()
            click.echo(f"hoistsim: internal error: {type(exc).__name__}: {text[0] if text else ''} "
                       "(run again with --debug for the traceback)", err=True)
            sys.exit(RUN_FAILED)

    return wrapper


debug_option = click.option("--debug", is_flag=True, help="Show Python tracebacks on errors.")


class _OneLineErrors(click.Group):
    """click's usage errors (a missing option, a folder given for a file) as one line, exit 2."""

    def main(self, *args, **kwargs):
        kwargs["standalone_mode"] = False
        try:
            status = super().main(*args, **kwargs)
        except click.exceptions.NoArgsIsHelpError as exc:  # plain `hoistsim`: show the help
            click.echo(exc.ctx.get_help())
            sys.exit(0)
        except click.ClickException as exc:
            click.echo(f"hoistsim: error: {exc.format_message()} (see hoistsim --help)", err=True)
            sys.exit(exc.exit_code)
        except click.exceptions.Abort:
            click.echo("hoistsim: interrupted", err=True)
            sys.exit(130)
        if isinstance(status, int):
            sys.exit(status)


@click.group(cls=_OneLineErrors, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="hoistsim")
def main():
    """Start-up of a winch hoist: motor, cone clutch (stick-slip), gears, drum and load."""


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "output", required=True, type=click.Path(dir_okay=False),
              help="HDF5 file to write (replaced atomically).")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE",
              help='Override a scenario key, e.g. --set clutch.engagement_force="2500 N". Repeatable.')
@click.option("--sweep", "sweeps", multiple=True, metavar="KEY=V1,V2,..|KEY=FROM:TO:COUNT",
              help='Sweep a key (replaces the file\'s sweep:), e.g. --sweep "clutch.engagement_force=1 kN:9 kN:100". '
                   "Twice: every combination.")
@click.option("--summary-only", is_flag=True,
              help="Keep only each run's summary, no time series: for very large sweeps.")
@click.option("--resume", is_flag=True,
              help="Finish a sweep that was interrupted, keeping the chunks already written "
                   "(the same scenario and options).")
@click.option("--workers", type=int, metavar="N",
              help="Run the sweep on a local Dask cluster of N processes (pip install -e \".[cluster]\").")
@click.option("--scheduler", metavar="ADDRESS",
              help="Run the sweep on a running Dask cluster, e.g. tcp://10.0.0.5:8786.")
@debug_option
@_guarded
def run(scenario, output, overrides, sweeps, summary_only, resume, workers, scheduler):
    """Simulate SCENARIO (every sweep value, when it has a sweep) and write OUTPUT."""
    scenario_path = scenario
    scenario = _scenario(scenario_path, overrides, sweeps)
    target = Path(output)
    if target.suffix.lower() not in RESULT_SUFFIXES:
        _fail(f"{output}: results are HDF5: name the file .h5, .hdf5 or .nc")
    if not target.parent.exists() and str(target.parent):
        _fail(f"{output}: the folder {target.parent} does not exist")

    from . import _jax
    from .output import write_runs
    from .report import periodic_table, summary_table
    from .simulation import SimulationError, simulate

    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    command = "hoistsim run " + " ".join(
        [scenario_path, "-o", output, *(f"--set {o}" for o in overrides), *(f"--sweep {w}" for w in sweeps)]
        + (["--summary-only"] if summary_only else []))
    from .streaming import ResumeError

    started = time.perf_counter()
    if resume and not (scenario.sweep or summary_only):
        _fail("--resume: only a sweep (or --summary-only) is written in chunks; run it again instead")
    if workers is not None and scheduler is not None:
        _fail("give either --workers (a local cluster) or --scheduler (a running one), not both")
    if workers is not None and workers < 1:
        _fail(f"--workers: needs at least 1, got {workers}")
    from .cluster import ClusterError, ClusterLost

    clustered = workers is not None or scheduler is not None
    try:
        if scenario.sweep or summary_only or clustered:  # written block by block as the runs finish
            from .sweeps import sweep

            result = sweep(scenario, summary_only=summary_only, progress=progress_printer(), output=target,
                           command=command, resume=resume, workers=workers, scheduler=scheduler)
            summaries, warnings = result.summaries, result.warnings
        else:  # one run: the plain compiled loop, kept in the persistent cache
            one = simulate(scenario)
            write_runs(target, [one], command=command)
            summaries, warnings = [one.summary], one.warnings
    except SimulationError as exc:
        _fail(str(exc), RUN_FAILED)
    except ResumeError as exc:
        _fail(f"--resume: {exc}")
    except ClusterLost as exc:  # during the run: not the input's fault
        _fail(str(exc), RUN_FAILED)
    except ClusterError as exc:
        _fail(str(exc))
    except OSError as exc:  # the results file could not be written (a full disk, no permission)
        _fail(f"{output}: cannot write: {exc.strerror or exc}")
    for warning in warnings[:5]:
        click.echo(f"hoistsim: warning: {warning}", err=True)
    if len(warnings) > 5:
        click.echo(f"hoistsim: warning: ... and {len(warnings) - 5} more runs like these", err=True)
    elapsed = time.perf_counter() - started
    click.echo(summary_table(summaries))
    if "irregularity" in summaries[0]:
        click.echo("periodic regime of the motor shaft:")
        click.echo(periodic_table(summaries))
    count = len(summaries)
    click.echo(f"wrote {output} ({count} run{'s' if count != 1 else ''}"
               f"{', summaries only' if summary_only else ''}, {elapsed:.2f} s)")


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False),
              help="HDF5 file to rewrite (atomically) after each run.")
@click.option("--plot", "figure", type=click.Path(dir_okay=False), metavar="FIG.png",
              help="Figure to redraw (atomically) after each run: .png, .svg or .pdf.")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@debug_option
@_guarded
def watch(scenario, output, figure, overrides):
    """Run SCENARIO again at each save: results, figure and the run's headline, in a process kept warm.

    A new value runs without compiling; a new structure compiles once.  A bad edit prints its error
    and the last good results are kept.  Ctrl-C stops.
    """
    from . import _jax
    from .watching import Watch, watch as watch_loop

    if output is not None and Path(output).suffix.lower() not in RESULT_SUFFIXES:
        _fail(f"{output}: results are HDF5: name the file .h5, .hdf5 or .nc")
    if figure is not None and Path(figure).suffix.lower() not in (".png", ".svg", ".pdf"):
        _fail(f"{figure}: the figure must be .png, .svg or .pdf")
    for path in (output, figure):
        if path is not None and str(Path(path).parent) and not Path(path).parent.exists():
            _fail(f"{path}: the folder {Path(path).parent} does not exist")
    if not Path(scenario).is_file():
        _fail(f"{scenario}: no such scenario file")
    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    watched = Watch(Path(scenario), output=output and Path(output), figure=figure and Path(figure),
                    overrides=overrides, echo=lambda line: click.echo(line, err=line.startswith("hoistsim:")))
    click.echo(f"watching {scenario} (Ctrl-C stops)", err=True)
    try:
        watch_loop(watched)
    finally:
        watched.close()


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@debug_option
@_guarded
def check(scenario, overrides):
    """Validate SCENARIO and print the reduced model, without simulating."""
    from .report import machine_table
    from .sweep_runs import SweepRuns

    scenario_path = scenario
    scenario = _scenario(scenario_path, overrides)
    count = len(SweepRuns(scenario))  # every value was validated as the file was read
    click.echo(machine_table(scenario))
    click.echo(f"{scenario_path}: valid ({count} run{'s' if count != 1 else ''})")


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print the answers as a JSON object (SI units).")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@debug_option
@_guarded
def statics(scenario, as_json, overrides):
    """The exercise's static answers for SCENARIO's machine: clutch force, heaviest load, bearing loads."""
    import json

    from .report import fmt, table
    from .schema_drivetrain import hoist_only
    from .statics import answers, warnings

    scenario = _scenario(scenario, overrides)
    hoist_only(scenario, "statics")
    rows = answers(scenario)
    for warning in warnings(scenario):
        click.echo(f"hoistsim: warning: {warning}", err=True)
    if as_json:
        click.echo(json.dumps({a.key: a.value for a in rows}, indent=2))
        return
    click.echo(f"{scenario.name}: static answers (uniform-wear clutch radius unless the scenario says otherwise)")
    click.echo(table(["symbol", "quantity", "value", "unit"],
                     [[a.symbol, a.quantity, fmt(a.value, 5), a.unit] for a in rows], align="llrl"))
    if scenario.bearings is None:
        click.echo("(add a bearings: section for the bearing reactions)")


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("--irregularity", required=True, type=float, metavar="DELTA",
              help="Degree of irregularity to meet, (w_max - w_min) / w_mean, e.g. 0.01.")
@click.option("--json", "as_json", is_flag=True, help="Print the answers as a JSON object (SI units).")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@click.option("--density", metavar="QUANTITY", help='Rim material, e.g. "7200 kg/m^3": also size a rim.')
@click.option("--width", metavar="QUANTITY", help='Rim width (axial), e.g. "8 cm": gives the outer diameter.')
@click.option("--outer-diameter", metavar="QUANTITY", help='Rim outer diameter, e.g. "60 cm": gives the width.')
@click.option("--inner-diameter", metavar="QUANTITY", default="0 m", show_default=True,
              help="Rim inner diameter (0: a solid disc).")
@click.option("--plot", "figure", type=click.Path(dir_okay=False), metavar="FIG.png",
              help="Also draw delta against flywheel inertia, simulated and by Tredgold.")
@debug_option
@_guarded
def flywheel(scenario, irregularity, as_json, overrides, density, width, outer_diameter, inner_diameter, figure):
    """Size a flywheel for SCENARIO's machine: Tredgold's, and the one with which the simulation meets DELTA.

    The flywheel goes on flywheel.shaft (the motor shaft if the scenario has none).  The machine is
    first run as given, with its own flywheel if it has one (it must reach its periodic regime: give a
    flywheel for a machine that does not run without); the answers replace that flywheel.
    """
    import json

    from . import _jax, units
    from .periodic.flywheel import rim, size_flywheel
    from .schema_drivetrain import hoist_only

    if figure is not None and Path(figure).suffix.lower() not in (".png", ".svg", ".pdf"):
        _fail(f"{figure}: the figure must be .png, .svg or .pdf")
    scenario = _scenario(scenario, overrides)
    hoist_only(scenario, "flywheel")

    def quantity(option, value, dimension):
        try:
            return units.to_si(value, dimension)
        except ValueError as exc:
            raise ScenarioError(option, str(exc)) from None

    rim_sizes = None
    if density is not None:
        rim_sizes = {"density": quantity("--density", density, units.DENSITY),
                     "inner_diameter": quantity("--inner-diameter", inner_diameter, units.LENGTH),
                     "width": None if width is None else quantity("--width", width, units.LENGTH),
                     "outer_diameter": None if outer_diameter is None else quantity("--outer-diameter",
                                                                                      outer_diameter, units.LENGTH)}
        rim(1.0, **{k: v for k, v in rim_sizes.items()})  # checks the options before any run
    elif width is not None or outer_diameter is not None:
        _fail("--width and --outer-diameter need --density (the rim's material)")
    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    started = time.perf_counter()
    sizing = size_flywheel(scenario, irregularity)
    if rim_sizes is not None:
        sizing.rim = rim(sizing.flywheel_inertia, **rim_sizes)
    elapsed = time.perf_counter() - started
    if figure is not None:
        from .plotting_periodic import flywheel_figure

        flywheel_figure(sizing, figure, title=scenario.name)
    if as_json:
        click.echo(json.dumps(sizing.as_dict(), indent=2))
    else:
        from .report import flywheel_table

        click.echo(flywheel_table(scenario.name, sizing, elapsed))
    if figure is not None:
        click.echo(f"wrote {figure}", err=as_json)


@main.command()
@click.option("--smoke", is_flag=True, help="A few tolerances on one scene (seconds), nothing written.")
@click.option("-o", "--output", "output", default="benchmarks/results", show_default=True,
              type=click.Path(file_okay=False), help="Folder for work_precision.csv and .png.")
@debug_option
@_guarded
def bench(smoke, output):
    """The work-precision study: error against time for every method, against the closed-form solution."""
    from .study import main as study

    study(smoke=smoke, output=output)


@main.command()
@click.argument("results", type=click.Path(dir_okay=False))
@click.option("--csv", "as_csv", is_flag=True,
              help="Every summary column as CSV on stdout: a header row, a units row, then the runs (SI).")
@click.option("--columns", metavar="NAME,NAME,...", help="The summary columns to show, in this order.")
@debug_option
@_guarded
def compare(results, as_csv, columns):
    """Compare the runs of RESULTS (an HDF5 file): one row per run, the summary as columns.

    By default as many columns as fit 120 characters, the questions first (lock-up, heat, torque,
    where the load went); units under the names.
    """
    from .reading import read_summary, read_summary_units
    from .report import compare_table

    rows = _read(read_summary, results)
    units = _read(read_summary_units, results)
    if as_csv:
        import csv

        writer = csv.writer(sys.stdout, lineterminator="\n")
        writer.writerow(list(rows[0]))
        writer.writerow([units.get(name, "") for name in rows[0]])
        writer.writerows([list(row.values()) for row in rows])
        return
    chosen = [c.strip() for c in columns.split(",") if c.strip()] if columns else None
    try:
        click.echo(compare_table(rows, units, chosen))
    except ValueError as exc:
        _fail(f"--columns: {exc}")


def _read(reader, path):
    if not Path(path).is_file():
        _fail(f"{path}: no such results file")
    try:
        return reader(path)
    except (OSError, KeyError) as exc:
        _fail(f"{path}: not a hoistsim results file ({exc})")


@main.command()
@click.argument("results", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "output", required=True, type=click.Path(dir_okay=False),
              help="Figure file: .png, .svg or .pdf.")
@debug_option
@_guarded
def plot(results, output):
    """Plot speed and clutch-slip histories of every run in RESULTS (an HDF5 file).

    A machine with a periodic regime also gets OUTPUT's name + "_periodic": the
    turning-moment diagram and the speed over a period (of the first run).
    A sweep also gets a second figure, OUTPUT's name + "_summary": lock-up time,
    clutch heat, peak torque and lowest load position against the swept value.
    A summary-only file gets that figure alone, as OUTPUT.
    """
    suffix = Path(output).suffix.lower()
    if suffix not in (".png", ".svg", ".pdf"):
        _fail(f"{output}: the figure must be .png, .svg or .pdf")
    if not Path(output).parent.exists() and str(Path(output).parent):
        _fail(f"{output}: the folder {Path(output).parent} does not exist")
    from .plotting import plot_file

    for written in _read(lambda path: plot_file(path, output), results):
        click.echo(f"wrote {written}")


if __name__ == "__main__":  # pragma: no cover
    main()

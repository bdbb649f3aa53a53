"""`hoistsim run`, `watch` and `check`: a scenario run, run again at each save, or checked."""

from __future__ import annotations

import time
from pathlib import Path

import click

from .group import (RESULT_SUFFIXES, RUN_FAILED, debug_option, exit_when_done, fail, main, one_line_errors,
                    read_scenario, strict_here, strict_option)
from .terminal import compiling, progress_printer, table_width


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
@click.option("--wide", is_flag=True,
              help="Print the summary table in one piece, however wide (by default its columns are stacked in "
                   "blocks that fit the terminal: COLUMNS, or 100 characters when not a terminal).")
@click.option("--csv", "as_csv", is_flag=True,
              help="Print every run's summary as CSV on stdout instead of the table (as hoistsim compare --csv; "
                   "the closing line goes to stderr).")
@strict_option
@debug_option
@one_line_errors
def run(scenario, output, overrides, sweeps, summary_only, resume, workers, scheduler, wide, as_csv):
    """Simulate SCENARIO (every sweep value, when it has a sweep) and write OUTPUT.

    Every key of a scenario file, its unit, default and range: docs/scenario.md.
    """
    from ..program_hints import command_hint, programs_wanted, remember_programs

    scenario_path = scenario
    hint = command_hint(scenario_path, overrides, sweeps, summary_only)
    wanted = programs_wanted(hint)
    if wanted:  # this command ran before: its stored programs load while the scenario is read
        from .. import _jax

        _jax.enable_compilation_cache()
        _jax.preload(wanted)
        # bad input ends the process at its one-line error, not after the program being read and JAX's teardown
        exit_when_done()
    scenario = read_scenario(scenario_path, overrides, sweeps)
    target = Path(output)
    if target.suffix.lower() not in RESULT_SUFFIXES:
        fail(f"{output}: results are HDF5: name the file .h5, .hdf5 or .nc")
    if not target.parent.exists() and str(target.parent):
        fail(f"{output}: the folder {target.parent} does not exist")
    exit_when_done(False)  # from here on the command may leave a cluster to stop

    from .. import _jax
    from ..results.output import write_runs
    from ..results.report import csv_text, periodic_table, summary_table
    from ..running.simulation import SimulationError, simulate

    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    command = "hoistsim run " + " ".join(
        [scenario_path, "-o", output, *(f"--set {o}" for o in overrides), *(f"--sweep {w}" for w in sweeps)]
        + (["--summary-only"] if summary_only else []))
    from ..running.streaming import ResumeError

    started = time.perf_counter()
    if resume and not (scenario.sweep or summary_only):
        fail("--resume: only a sweep (or --summary-only) is written in chunks; run it again instead")
    if workers is not None and scheduler is not None:
        fail("give either --workers (a local cluster) or --scheduler (a running one), not both")
    if workers is not None and workers < 1:
        fail(f"--workers: needs at least 1, got {workers}")
    from ..running.cluster import ClusterError, ClusterLost

    clustered = workers is not None or scheduler is not None
    try:
        with _jax.serving_recorded() as served:
            if scenario.sweep or summary_only or clustered:  # written block by block as the runs finish
                from ..running.sweeps import sweep

                result = sweep(scenario, summary_only=summary_only, progress=progress_printer(), output=target,
                               command=command, resume=resume, workers=workers, scheduler=scheduler)
                summaries, warnings = result.summaries, result.warnings
            else:  # one run: the plain compiled loop, kept in the persistent cache
                one = simulate(scenario)
                write_runs(target, [one], command=command)
                summaries, warnings = [one.summary], one.warnings
    except SimulationError as exc:
        fail(str(exc), RUN_FAILED)
    except ResumeError as exc:
        fail(f"--resume: {exc}")
    except ClusterLost as exc:  # during the run: not the input's fault
        fail(str(exc), RUN_FAILED)
    except ClusterError as exc:
        fail(str(exc))
    except OSError as exc:  # the results file could not be written (a full disk, no permission)
        fail(f"{output}: cannot write: {exc.strerror or exc}")
    if served != wanted:
        remember_programs(hint, served)
    for warning in warnings[:5]:
        click.echo(f"hoistsim: warning: {warning}", err=True)
    if len(warnings) > 5:
        click.echo(f"hoistsim: warning: ... and {len(warnings) - 5} more runs like these", err=True)
    elapsed = time.perf_counter() - started
    if as_csv:  # the file's own summary, as compare --csv reads it: the swept keys, the units row
        from ..results.reading import read_summary, read_summary_units

        click.echo(csv_text(read_summary(target), read_summary_units(target)), nl=False)
    else:
        width = table_width(wide)
        click.echo(summary_table(summaries, width=width))
        if "irregularity" in summaries[0]:
            click.echo("periodic regime of the motor shaft:")
            click.echo(periodic_table(summaries, width=width))
    count = len(summaries)
    click.echo(f"wrote {output} ({count} run{'s' if count != 1 else ''}"
               f"{', summaries only' if summary_only else ''}, {elapsed:.2f} s)", err=as_csv)
    if not clustered:  # a cluster's processes are stopped by the interpreter's teardown
        exit_when_done()


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "output", type=click.Path(dir_okay=False),
              help="HDF5 file to rewrite (atomically) after each run.")
@click.option("--plot", "figure", type=click.Path(dir_okay=False), metavar="FIG.png",
              help="Figure to redraw (atomically) after each run: .png, .svg or .pdf.")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@strict_option
@debug_option
@one_line_errors
def watch(scenario, output, figure, overrides):
    """Run SCENARIO again at each save: results, figure and the run's headline, in a process kept warm.

    A new value runs without compiling; a new structure compiles once.  A bad edit prints its error
    and the last good results are kept.  Ctrl-C stops.
    """
    from .. import _jax
    from .watching import Watch
    from .watching import watch as watch_loop

    if output is not None and Path(output).suffix.lower() not in RESULT_SUFFIXES:
        fail(f"{output}: results are HDF5: name the file .h5, .hdf5 or .nc")
    if figure is not None and Path(figure).suffix.lower() not in (".png", ".svg", ".pdf"):
        fail(f"{figure}: the figure must be .png, .svg or .pdf")
    for path in (output, figure):
        if path is not None and str(Path(path).parent) and not Path(path).parent.exists():
            fail(f"{path}: the folder {Path(path).parent} does not exist")
    if not Path(scenario).is_file():
        fail(f"{scenario}: no such scenario file")
    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    watched = Watch(Path(scenario), output=output and Path(output), figure=figure and Path(figure),
                    overrides=overrides, strict=strict_here(), echo=lambda line: click.echo(line, err=line.startswith("hoistsim:")))
    click.echo(f"watching {scenario} (Ctrl-C stops)", err=True)
    try:
        watch_loop(watched)
    finally:
        watched.close()


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@click.option("--drivetrain", "as_drivetrain", is_flag=True,
              help="Print the drivetrain a hoist scenario stands for, as a scenario file (shafts, clutch, gears, ...).")
@strict_option
@debug_option
@one_line_errors
def check(scenario, overrides, as_drivetrain):
    """Validate SCENARIO and print the reduced model and the parts it is built from, without simulating."""
    from ..studies.machine_tables import machine_table
    from ..scenario.sweep_runs import SweepRuns

    scenario_path = scenario
    scenario = read_scenario(scenario_path, overrides)
    if as_drivetrain:
        from ..studies.hoist_drawing import hoist_as_drivetrain_text

        click.echo(hoist_as_drivetrain_text(scenario), nl=False)
        return
    count = len(SweepRuns(scenario))  # every value was validated as the file was read
    click.echo(machine_table(scenario, table_width()))
    click.echo(f"{scenario_path}: valid ({count} run{'s' if count != 1 else ''})")

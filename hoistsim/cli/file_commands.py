"""`hoistsim compare` and `plot`: what a results file holds, as a table or as figures."""

from __future__ import annotations

from pathlib import Path

import click

from .group import debug_option, fail, main, one_line_errors
from .terminal import table_width


@main.command()
@click.argument("results", type=click.Path(dir_okay=False))
@click.option("--csv", "as_csv", is_flag=True,
              help="Every summary column as CSV on stdout: a header row, a units row, then the runs (SI).")
@click.option("--columns", metavar="NAME,NAME,...",
              help="The summary columns to show, in this order (in stacked blocks where they do not fit).")
@click.option("--wide", is_flag=True, help="Every column in one table, however wide the terminal.")
@debug_option
@one_line_errors
def compare(results, as_csv, columns, wide):
    """Compare the runs of RESULTS (an HDF5 file): one row per run, the summary as columns.

    By default as many columns as fit the terminal (COLUMNS, or 100 characters when not a terminal),
    the questions first (lock-up, heat, where the load went, torque); each summary headed, in the unit and
    number format `run` prints it in (heat in kJ, speeds in rpm; --csv keeps the file's SI and names), units
    under the names. A sweep's runs are named by their swept values (by their labels with --wide).
    """
    from ..results.reading import read_summary, read_summary_units
    from ..results.report import compare_table, csv_text

    rows = _read(read_summary, results)
    units = _read(read_summary_units, results)
    if as_csv:
        click.echo(csv_text(rows, units), nl=False)
        return
    chosen = [c.strip() for c in columns.split(",") if c.strip()] if columns else None
    try:
        click.echo(compare_table(rows, units, chosen, table_width(wide)))
    except ValueError as exc:
        fail(f"--columns: {exc}")


def _read(reader, path):
    if not Path(path).is_file():
        fail(f"{path}: no such results file")
    try:
        return reader(path)
    except (OSError, KeyError):
        fail(f"{path}: not a hoistsim results file: {_what_it_seems(path)}; hoistsim writes one with `hoistsim run "
             "SCENARIO -o FILE.h5` (its top holds runs and scenario)")


def _what_it_seems(path) -> str:
    """What a file that is no hoistsim results file seems to be, in a few words: an HDF5 file and what its top
    holds, or not HDF5 at all."""
    import h5py

    if not h5py.is_hdf5(path):
        return "it is not an HDF5 file at all"
    try:
        with h5py.File(path, "r") as f:
            top = sorted(f)
    except OSError:
        return "an HDF5 file that does not open"
    if not top:
        return "an empty HDF5 file"
    shown = ", ".join(top[:5]) + (f" and {len(top) - 5} more" if len(top) > 5 else "")
    return f"an HDF5 file whose top holds {shown}"


@main.command()
@click.argument("results", type=click.Path(dir_okay=False))
@click.option("-o", "--output", "output", required=True, type=click.Path(dir_okay=False),
              help="Figure file: .png, .svg or .pdf.")
@debug_option
@one_line_errors
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
        fail(f"{output}: the figure must be .png, .svg or .pdf")
    if not Path(output).parent.exists() and str(Path(output).parent):
        fail(f"{output}: the folder {Path(output).parent} does not exist")
    from ..figures.files import plot_file

    for written in _read(lambda path: plot_file(path, output), results):
        click.echo(f"wrote {written}")

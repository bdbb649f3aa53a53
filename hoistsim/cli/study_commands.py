"""`hoistsim statics`, `flywheel` and `bench`: the answers computed from a scenario rather than run in time."""

from __future__ import annotations

import time
from pathlib import Path

import click

from ..errors import ScenarioError
from .group import debug_option, fail, main, one_line_errors, read_scenario, strict_option
from .terminal import compiling, table_width


@main.command()
@click.argument("scenario", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print the answers as a JSON object (SI units).")
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@strict_option
@debug_option
@one_line_errors
def statics(scenario, as_json, overrides):
    """The exercise's static answers for SCENARIO's machine: clutch force, heaviest load, bearing loads."""
    import json

    from ..results.report import fmt, note, table
    from ..scenario.schema_drivetrain import hoist_only
    from ..studies.statics import answers, warnings

    scenario = read_scenario(scenario, overrides)
    hoist_only(scenario, "statics")
    rows = answers(scenario)
    for warning in warnings(scenario):
        click.echo(f"hoistsim: warning: {warning}", err=True)
    if as_json:
        click.echo(json.dumps({a.key: a.value for a in rows}, indent=2))
        return
    width = table_width()
    click.echo(note(f"{scenario.name}: static answers (uniform-wear clutch radius unless the scenario says "
                    "otherwise)", width))
    click.echo(table(["symbol", "quantity", "value", "unit"],
                     [[a.symbol, a.quantity, fmt(a.value, 5), a.unit] for a in rows], align="llrl", width=width))
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
@strict_option
@debug_option
@one_line_errors
def flywheel(scenario, irregularity, as_json, overrides, density, width, outer_diameter, inner_diameter, figure):
    """Size a flywheel for SCENARIO's machine: Tredgold's, and the one with which the simulation meets DELTA.

    The flywheel goes on flywheel.shaft (the motor shaft if the scenario has none).  The machine is
    first run as given, with its own flywheel if it has one (it must reach its periodic regime: give a
    flywheel for a machine that does not run without); the answers replace that flywheel.
    """
    import json

    from .. import _jax
    from ..scenario import units
    from ..scenario.schema_drivetrain import hoist_only
    from ..studies.flywheel import rim, size_flywheel

    if figure is not None and Path(figure).suffix.lower() not in (".png", ".svg", ".pdf"):
        fail(f"{figure}: the figure must be .png, .svg or .pdf")
    scenario = read_scenario(scenario, overrides)
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
        fail("--width and --outer-diameter need --density (the rim's material)")
    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    started = time.perf_counter()
    sizing = size_flywheel(scenario, irregularity)
    if rim_sizes is not None:
        sizing.rim = rim(sizing.flywheel_inertia, **rim_sizes)
    elapsed = time.perf_counter() - started
    if figure is not None:
        from ..figures.periodic import flywheel_figure

        flywheel_figure(sizing, figure, title=scenario.name)
    if as_json:
        click.echo(json.dumps(sizing.as_dict(), indent=2))
    else:
        from ..results.report import flywheel_table

        click.echo(flywheel_table(scenario.name, sizing, elapsed, table_width()))
    if figure is not None:
        click.echo(f"wrote {figure}", err=as_json)


@main.command()
@click.option("--smoke", is_flag=True, help="A few tolerances on one scene (seconds), nothing written.")
@click.option("-o", "--output", "output", default="benchmarks/results", show_default=True,
              type=click.Path(file_okay=False), help="Folder for work_precision.csv and .png.")
@debug_option
@one_line_errors
def bench(smoke, output):
    """The work-precision study: error against time for every method, against the closed-form solution."""
    from ..studies.work_precision import main as study

    study(smoke=smoke, output=output)

"""`hoistsim sensitivity`: how far each summary moves with each key, derivatives through every switch."""

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
@click.option("--set", "overrides", multiple=True, metavar="KEY=VALUE", help="Override a scenario key.")
@strict_option
@debug_option
@one_line_errors
def sensitivity(scenario, wrt, of, as_json, overrides):
    """How far each summary of SCENARIO moves with each key: its derivative, exact through every switch,
    and its elasticity (key / summary x derivative: the summary's relative change per relative change of
    the key).  A summary that does not exist (a lock-up that never comes) has none: '-'."""
    import json

    from .. import _jax
    from ..results.report import sensitivity_table
    from ..running.sensitivity import sensitivity as differentiate

    scenario = read_scenario(scenario, overrides)
    _jax.enable_compilation_cache()
    _jax.compile_notice = compiling
    from ..running.simulation import SimulationError

    try:
        result = differentiate(scenario, _names(wrt), _names(of))
    except SimulationError as exc:  # a run that cannot be completed (a chattering clutch): exit 1
        fail(str(exc), RUN_FAILED)
    if as_json:
        click.echo(json.dumps(result.to_dict(), indent=2))
        return
    click.echo(sensitivity_table(result, table_width()))

"""The `hoistsim` group and what every command shares: reading a scenario, one-line errors, exit statuses.

Exit status: 0 success, 1 a run that could not be completed (chattering, solver
failure), 2 bad input (scenario, options, files).  Errors are one line on
stderr; --debug shows the traceback.
"""

from __future__ import annotations

import functools
import os
import sys

# Before equinox is imported: its runtime checks become NaNs rather than host
# callbacks, so compiled runs can be kept in the persistent cache.  A library
# user's own equinox code is left as it is; only the command line sets this.
os.environ.setdefault("EQX_ON_ERROR", "nan")

import click  # noqa: E402

from ..errors import ScenarioError  # noqa: E402

BAD_INPUT, RUN_FAILED = 2, 1


class Failure(Exception):
    def __init__(self, message: str, status: int):
        super().__init__(message)
        self.status = status


# Names a results file may take: what HDF5 and netCDF-4 readers (h5py, xarray) expect.
RESULT_SUFFIXES = (".h5", ".hdf5", ".nc")


def read_scenario(path, overrides=(), sweeps=()):
    """Load and validate a scenario; what it accepted but may not mean (a bare number on a length, a 40 m drum)
    is said on stderr, one line each, or is an error where the command was given --strict."""
    from ..scenario.loading import load_scenario

    scenario = load_scenario(path, overrides=list(overrides), sweeps=list(sweeps), strict=strict_here())
    for warning in scenario.warnings:
        click.echo(f"hoistsim: warning: {warning}", err=True)
    return scenario


def fail(message: str, status: int = BAD_INPUT):
    raise Failure(message, status)


def one_line_errors(func):
    """Turn known failures into one line on stderr and an exit status (``--debug``: raise)."""

    @functools.wraps(func)
    def wrapper(*, debug: bool = False, **kwargs):
        try:
            return func(**kwargs)
        except Failure as exc:
            if debug:
                raise
            click.echo(f"hoistsim: error: {exc}", err=True)
            sys.exit(exc.status)
        except ScenarioError as exc:
            if debug:
                raise
            for each in exc.each():  # one line each (--strict: every value it names)
                click.echo(f"hoistsim: error: {each}", err=True)
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

# A command that reads a scenario takes --strict: what would be a warning on its values is an error.
strict_option = click.option(
    "--strict", is_flag=True, expose_value=False, callback=lambda ctx, _, value: ctx.meta.update(strict=value),
    help="Make the warnings on the scenario's values errors (exit 2): a bare number on a key with a unit (read "
         "in SI: 40 on a diameter is 40 m), a value far outside what its part measures.")


def strict_here() -> bool:
    """Whether the running command was given --strict."""
    ctx = click.get_current_context(silent=True)
    return bool(ctx is not None and ctx.meta.get("strict"))


# Set by a command that has finished and left nothing to tidy (see exit_when_done).
_nothing_left_to_tidy = False


def exit_when_done(done: bool = True) -> None:
    """Let the process end as soon as the command returns or fails, without the interpreter's teardown
    (``done=False``: with it again).

    Tearing down a process that used JAX takes some 0.4 s on 2 cores (XLA's
    client and its programs, every module's objects), a fifth of a warm `run`.
    A command calls this once its files are written and closed and its output
    printed, or while nothing it could fail at leaves anything open; only the
    command line itself exits early (a caller in the same process, a test's
    CliRunner, goes on as usual).
    """
    global _nothing_left_to_tidy
    _nothing_left_to_tidy = done


class OneLineErrors(click.Group):
    """click's usage errors (a missing option, a folder given for a file) as one line, exit 2."""

    def main(self, *args, **kwargs):
        kwargs["standalone_mode"] = False
        from_command_line = (args[0] if args else kwargs.get("args")) is None  # sys.argv, not a caller's list
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
        except SystemExit as exc:  # a command's one-line error and its status
            if not isinstance(exc.code, int):
                raise
            status = exc.code
        global _nothing_left_to_tidy
        done, _nothing_left_to_tidy = _nothing_left_to_tidy, False
        if from_command_line and done:
            try:
                sys.stdout.flush()
                sys.stderr.flush()
            except OSError:  # output piped into `head` and the like, closed: as one_line_errors says
                os._exit(1)
            os._exit(status if isinstance(status, int) else 0)
        if isinstance(status, int):
            sys.exit(status)


@click.group(cls=OneLineErrors, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(package_name="hoistsim")
def main():
    """Start-up of a winch hoist: motor, cone clutch (stick-slip), gears, drum and load."""

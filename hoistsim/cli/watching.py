"""`hoistsim watch`: the edit-run-look loop, in one warm process.

Each save of the scenario runs it again, rewrites the results and the figure
(each atomically) and prints the run's headline.  The process keeps every
program it compiled: a new value runs at once, a new structure compiles once
(and says so, through the compile notice).  A bad edit prints its one-line
error and the last good results stay as they were.  Files are watched with
``watchfiles`` (the operating system's notifications, not polling); an
editor's save by rename counts like a write.
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Callable, Iterable
from pathlib import Path

from ..errors import ScenarioError

# watchfiles gathers the events of one save for this long after the last (ms): an editor's save is
# a few events (write, rename, attributes) within a millisecond or two.
QUIET_MS = 20
# zlib's level for the figure: a viewer reloads it at every save, and the default level (6) costs a tenth of
# the wait for 15 % less file
PNG_COMPRESSION = 1


class Watch:
    """One scenario file, its results file and figure: :meth:`run` runs it again and says what came out."""

    def __init__(self, scenario: Path, *, output: Path | None = None, figure: Path | None = None,
                 overrides: Iterable[str] = (), strict: bool = False, echo: Callable[[str], None] = print):
        self.scenario = Path(scenario)
        self.overrides = list(overrides)
        self.strict = strict  # a value the scenario's warnings name is an error (--strict)
        self.figure = Path(figure) if figure is not None else None
        self._scratch = None  # a folder for a results file where the user asked for none (made when needed)
        self.output = Path(output) if output is not None else None
        self.echo = echo
        self.runs = 0  # runs that wrote results
        self._frames = None  # the figure's frame, kept from one run to the next (made at the first figure)
        self._read: bytes | None = None  # the scenario file as the last run read it

    def files(self) -> list[Path]:
        """The files whose saves run the scenario again (a scenario names no other file today)."""
        return [self.scenario.resolve()]

    def concerns(self, _change, path: str) -> bool:
        """Whether a file event is a save of a watched file (watchfiles' filter)."""
        return Path(path).resolve() in self.files()

    def _contents(self) -> bytes | None:
        try:
            return self.scenario.read_bytes()
        except OSError:
            return None

    def saved_since_run(self) -> bool:
        """Whether the scenario file changed after the last run read it."""
        return self._contents() != self._read

    def run(self) -> bool:
        """Load and simulate, print the headline, write the results and draw the figure (side by side); or print
        the error and that the last results stay.

        True where new results were written.
        """
        from ..running.simulation import SimulationError, simulate
        from ..scenario.lowering import output_names

        started = time.perf_counter()
        self._read = self._contents()  # before loading: a save from here on is a change the run did not see
        try:
            scenario = self._load()
            result = simulate(scenario)
        except (ScenarioError, SimulationError) as exc:
            kept = " (the last good results are kept)" if self.runs else ""
            *others, last = exc.each() if isinstance(exc, ScenarioError) else (exc,)
            for each in others:  # --strict: every value it names, one line each
                self.echo(f"hoistsim: error: {each}")
            self.echo(f"hoistsim: error: {last}{kept}")
            return False
        # the answer first: the file and the figure take some tenths of a second more
        said = "; ".join(_headline(result.summary, result.events, output_names(scenario)))
        self.echo(f"{time.strftime('%H:%M:%S')} {scenario.name}: {said} ({time.perf_counter() - started:.2f} s)")
        drawn = None
        if self.figure is not None and result.periodic is None:  # drawn from the run, written beside the file
            drawn = self._draw([result])
        output = self.output
        if output is None and self.figure is not None and drawn is None:  # a periodic regime: from a file
            if self._scratch is None:
                self._scratch = tempfile.TemporaryDirectory(prefix="hoistsim-watch-")
            output = Path(self._scratch.name) / "results.h5"
        try:
            if output is not None:
                from ..results.output import write_runs

                write_runs(output, [result], command=f"hoistsim watch {self.scenario}")
        finally:
            if drawn is not None:
                drawn.join()
        self.runs += 1
        if drawn is None and self.figure is not None:  # a periodic regime's figures are drawn from its file
            from ..figures.files import plot_file

            plot_file(output, self.figure, frames=self._kept_frames(), png_compression=PNG_COMPRESSION)
        return True

    def _kept_frames(self):
        from ..figures.frames import KeptFrames

        self._frames = self._frames or KeptFrames()
        return self._frames

    def _draw(self, results):
        """The runs' figure drawn now, its file written by a thread (returned) while the results are written."""
        from ..figures.files import draw_runs_figure, runs_columns
        from ..results.run_dicts import run_dicts
        from ..scenario.lowering import output_names

        columns = runs_columns(output_names(results[0].scenario))
        return draw_runs_figure(run_dicts(results, columns=columns), self.figure, frames=self._kept_frames(),
                                png_compression=PNG_COMPRESSION)

    def _load(self):
        from ..scenario.loading import load_scenario

        scenario = load_scenario(self.scenario, overrides=self.overrides, strict=self.strict)
        if scenario.sweep:
            raise ScenarioError("sweep", "watch runs one scenario: remove the sweep: section "
                                "(hoistsim run sweeps it)", source=str(self.scenario))
        for warning in scenario.warnings:
            self.echo(f"hoistsim: warning: {warning}")
        return scenario

    def close(self) -> None:
        if self._scratch is not None:
            self._scratch.cleanup()


def _headline(summary: dict, events: dict | None = None, names: dict | None = None) -> list[str]:
    """The run's headline, as its figure's title says it: with its events (columns), each clutch's story;
    ``names``: its names table (:func:`hoistsim.scenario.lowering.output_names`)."""
    from ..display import headline

    rows = None if events is None else [dict(zip(events, row)) for row in zip(*events.values())]
    said = headline(summary if rows is None else {**summary, "events": rows}, names)
    return said or [f"energy residual {summary.get('energy_relative_residual', float('nan')):.1e}"]


def watch(watched: Watch, stop_event=None) -> None:
    """Run once, then again at each save of a watched file, until ``stop_event`` is set (or Ctrl-C)."""
    import watchfiles

    watched.run()
    # The files are watched from here on: a save made during the first run (which compiles for seconds)
    # would be lost, so the file is compared with what that run read.
    while watched.saved_since_run():
        watched.run()
    folders = sorted({str(path.parent) for path in watched.files()})
    for _ in watchfiles.watch(*folders, watch_filter=watched.concerns, step=QUIET_MS, debounce=QUIET_MS * 10,
                              stop_event=stop_event, recursive=False, raise_interrupt=False):
        watched.run()

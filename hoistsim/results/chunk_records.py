"""A compiled chunk's runs as a results file's record, read straight from its arrays: no run made one by one.

A sweep streamed to a file with full output needs, of each run, its series on the output grid, its
instants with the series just after each, its summaries and its solver's counts.  All of them are in
the chunk's arrays (:class:`hoistsim.machine.core.readout.RawRun`, a leading axis of runs), and here
they are read for every run of the chunk at once, as :func:`.records.make_record` reads them from the
runs' :class:`hoistsim.results.run_result.RunResult`: the same numbers, bit for bit.  It applies where
every run of the chunk has the same output grid and no periodic regime to analyse.
"""

from __future__ import annotations

import numpy as np

from ..machine.core.element import MODE_NAMES
from ..machine.core.layout import Layout
from ..machine.core.ledger import balance_columns
from ..machine.core.readout import EVENT_COUNT, PASSES, REJECTED, STEPS, SWITCHES, BatchReadout
from .records import INSTANT_COLUMNS, TEXT_COLUMNS, Record, summary_values
from .run_summaries import summary_columns
from .summaries import Summaries

# the solver's counts a run keeps, as RunResult.stats names them, and where the loop's counters hold them
SOLVER_COUNTS = {"steps": STEPS, "rejected_steps": REJECTED, "segments": PASSES, "switches": SWITCHES}


def instant_categories(layout: Layout, kinds) -> np.ndarray:
    """Each instant's category by its kind: a threshold crossed (limit), an observation, a period mark
    (cycle), a switch, or else scheduled."""
    limits = {layout.name(kind) for element in layout.elements for kind in element.limits}
    cycles = [kind for _, _, kind in layout.cycles]
    return np.asarray(["limit" if k in limits else "observation" if k in layout.observation_kinds
                       else "cycle" if k in cycles else "switch" if k in layout.switch_kinds else "scheduled"
                       for k in kinds], dtype=object)


def chunk_record(layout: Layout, raw, count: int, grid: np.ndarray, indices, labels, elapsed: float) -> Record:
    """The first ``count`` runs of a chunk's raw outputs (numpy, on the host), each on the output ``grid``,
    as the record of runs ``indices`` (``labels``: theirs; ``elapsed``: the seconds each took)."""
    batch = BatchReadout(layout, raw, count)
    events = np.asarray(raw.counters[:count, EVENT_COUNT], dtype=np.int64)
    values = summary_values(Summaries(summary_columns(labels, batch.summary(), batch.ledger(), batch.count("lock"),
                                                      batch.count("unlock"))))
    extras = {f"energy_{key}": ("1" if key.endswith("relative_residual") else "J", np.asarray(v, dtype=float))
              for key, v in balance_columns(batch.ledger()).items()}
    for key, at in SOLVER_COUNTS.items():
        extras[f"solver_{key}"] = ("1", np.asarray(raw.counters[:count, at], dtype=np.int64))
    extras["solver_wall_time"] = ("s", np.full(count, elapsed))
    # the events of every run, one after another: (run, its k-th event)
    run = np.repeat(np.arange(count), events)
    k = np.arange(events.sum()) - np.repeat(np.cumsum(events) - events, events)
    times = np.asarray(raw.event_times[:count], dtype=float)[run, k]
    codes = np.asarray(raw.event_codes[:count])[run, k]
    last = _last_at_same_time(run, times[:, 0])  # the row an instant's time keeps: the last event at it
    columns = layout.columns()
    at_events = np.asarray(raw.event_columns[:count])[run, :, k]  # (events, columns)
    grid_values = np.array(np.asarray(raw.grid_columns[:count])[:, :, : grid.size])  # (runs, columns, rows)
    on_grid = np.searchsorted(grid, times[:, 0])
    hits = (on_grid < grid.size) & (grid[np.minimum(on_grid, grid.size - 1)] == times[:, 0]) & (last == np.arange(run.size))
    grid_values[run[hits], :, on_grid[hits]] = at_events[hits]  # a grid time with events at it: the state after them
    series, after = {}, {}
    for i, (name, (units, text)) in zip(layout.column_slots, columns.items()):
        block, behind = grid_values[:, i, :], at_events[last, i]
        if units == "1":  # a flag or a mode
            block, behind = block.astype(np.int8), behind.astype(np.int8)
        series[name] = (units, text, block)
        after[name] = behind
    kinds = np.asarray(layout.event_kinds, dtype=object)[codes[:, 0]]
    elements = np.asarray(layout.sections, dtype=object)[codes[:, 1]]
    instants = {"time": times[:, 0], "kind": kinds, "element": elements, "torque_margin": times[:, 1],
                "mode_after": _modes_after(layout, raw, run, k, codes[:, 1]),
                "category": instant_categories(layout, layout.event_kinds)[codes[:, 0]]}
    instants = {name: instants[name].astype(object) if name in TEXT_COLUMNS else instants[name].astype(float)
                for name in INSTANT_COLUMNS}
    return Record(np.asarray(indices, dtype=np.int64), values, extras=extras, series=series, counts=events,
                  instants=instants, after=after)


def _last_at_same_time(run: np.ndarray, times: np.ndarray) -> np.ndarray:
    """For each event, the last (in its run's log order) of its run's events at its time: the row a results
    file keeps for that time (it holds the state after them all)."""
    n = run.size
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    order = np.lexsort((np.arange(n), times, run))
    r, t = run[order], times[order]
    starts = np.append(True, (r[1:] != r[:-1]) | (t[1:] != t[:-1]))
    ends = np.append(np.flatnonzero(starts)[1:] - 1, n - 1)
    last = np.empty(n, dtype=np.int64)
    last[order] = order[ends[np.cumsum(starts) - 1]]
    return last


def _modes_after(layout: Layout, raw, run, k, element_codes) -> np.ndarray:
    """Each instant's coupling's mode after it ('' for an element that is no coupling)."""
    couplings = np.asarray([layout.coupling_names.index(s) if s in layout.coupling_names else -1
                            for s in layout.sections])[element_codes]
    if not layout.coupling_names:
        return np.full(run.size, "", dtype=object)
    names = np.full(max(MODE_NAMES) + 1, "", dtype=object)
    names[list(MODE_NAMES)] = list(MODE_NAMES.values())
    modes = np.asarray(raw.event_modes)[run, k, np.maximum(couplings, 0)]
    return np.where(couplings >= 0, names[modes], "").astype(object)

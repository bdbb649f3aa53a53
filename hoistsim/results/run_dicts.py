"""Runs in memory as the dicts the figures read: what :func:`.reading.read_runs` gives for their file.

``hoistsim watch`` draws a run's figure from the run itself while its results
file is written, instead of after it: the figure does not wait for the file.
The rows, the instants' table and the summary values come out as reading the
file back gives them (the same merge, the same types; tests/results/test_output.py
compares the two), so the figure is the one the file draws.
"""

from __future__ import annotations

import json

import numpy as np

from .records import summary_values
from .reading import events_table, merged_rows
from .summaries import Summaries


def run_dicts(results, columns=None) -> list[dict]:
    """A dict a run: ``time`` and the series (those in ``columns``, all when None) on the output grid with
    the state just after each instant put in, ``events``, and ``attrs`` (name, parameters, label, summary)."""
    if any(result.periodic is not None for result in results):
        raise ValueError("a periodic regime is read from its file (its periods and turning moment are made there)")
    first = results[0]
    base = {"name": first.scenario.name, "parameters": json.dumps(first.scenario.resolved(), sort_keys=True)}
    summaries = summary_values(Summaries.from_rows([result.summary for result in results]))
    runs = []
    for i, result in enumerate(results):
        wanted = [name for name in result.series if columns is None or name in columns]
        grid, after = result.grid_rows(), result.instant_rows()
        run = merged_rows(np.asarray(result.grid), {name: result.series[name][grid] for name in wanted},
                          np.asarray(result.instants["time"], dtype=float),
                          {name: result.series[name][after] for name in wanted})
        run["events"] = events_table(result.instants)
        run["attrs"] = {**base, "label": result.label or result.name,
                        **{key: values[i] for key, values in summaries.items()}}
        runs.append(run)
    return runs

"""Runs as records: what a block of finished runs adds to a results file, made in memory.

A record holds a block's summary values, its series on (run, time), its instants with the series just
after each, and its periodic regimes.  :mod:`.output` assembles a results file from records; one run
written at once is one record handed over in memory, and a streamed sweep keeps each record in a chunk
file (:func:`store_record`) and reads it back when the file is assembled (:func:`read_record`).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import h5py
import numpy as np

from .output_periodic import write_diagram, write_periods
from .summaries import Summaries

TEXT = h5py.string_dtype()

# What an instant row holds besides the series just after it, with its units and meaning.
INSTANT_COLUMNS = {
    "time": ("s", "the instant, exact (root-found or scheduled)"),
    "kind": ("1", "lock, unlock, reversal, engage, disengage, a scheduled event, an observation "
                  "(slip_peak, load_lowest, ...) or a period mark"),
    "element": ("1", "the element it belongs to"),
    "category": ("1", "switch, scheduled, observation, limit (a threshold crossed) or cycle"),
    "torque_margin": ("N*m", "the coupling's static capacity minus the torque it would carry stuck "
                             "(NaN where it does not apply)"),
    "mode_after": ("1", "the coupling's mode after it"),
}
TEXT_COLUMNS = ("kind", "element", "category", "mode_after")


@dataclass
class Record:
    """A block of runs as the results file takes them."""

    indices: np.ndarray  # each run's place in the sweep
    values: dict[str, np.ndarray]  # summary columns, in the elements' order
    extras: dict[str, tuple[str, np.ndarray]] = field(default_factory=dict)  # energy and solver: units, values
    series: dict[str, tuple[str, str, np.ndarray]] = field(default_factory=dict)  # units, meaning, (run, time)
    counts: np.ndarray | None = None  # instants a run (None: summaries only)
    instants: dict[str, np.ndarray] = field(default_factory=dict)  # INSTANT_COLUMNS (text as objects)
    after: dict[str, np.ndarray] = field(default_factory=dict)  # each series just after each instant
    periodic: dict = field(default_factory=dict)  # run's place in the block -> its Periodic, or an HDF5 group


def make_record(indices, outcomes, *, summary_only: bool, time, padded: bool) -> Record:
    """Runs at ``indices`` (RunResults, or their :class:`hoistsim.results.run_result.Summaries` when
    summary-only) as a record."""
    indices = np.asarray(list(indices), dtype=np.int64)
    if not summary_only:
        from .run_summaries import summaries_of  # the machine's ledger: a full run's record only
    values = summary_values(outcomes if summary_only else summaries_of(outcomes))
    if summary_only:
        return Record(indices, values)
    runs, first = outcomes, outcomes[0]
    series = {name: (first.units[name], first.descriptions.get(name, ""), block)
              for name, block in series_blocks(runs, time, padded).items()}
    tables = [run.instants for run in runs]
    instant_rows = [run.instant_rows() for run in runs]
    instants = {}
    for name in INSTANT_COLUMNS:
        values_ = np.concatenate([np.asarray(t[name]) for t in tables])
        instants[name] = values_.astype(object) if name in TEXT_COLUMNS else values_.astype(float)
    return Record(
        indices, values, extras=_run_extras(runs), series=series,
        counts=np.asarray([len(t["time"]) for t in tables], dtype=np.int64), instants=instants,
        after={name: np.concatenate([run.series[name][rows] for run, rows in zip(runs, instant_rows)])
               for name in first.series},
        periodic={k: run.periodic for k, run in enumerate(runs) if run.periodic is not None})


def joined(records: list[Record]) -> Record:
    """Records of runs kept apart (a block's chunks, a file's blocks) as one, its runs in the order of their
    indices (each run's instants kept together, in their order)."""
    if len(records) == 1 and np.all(np.diff(records[0].indices) > 0):
        return records[0]
    indices = np.concatenate([r.indices for r in records])
    order = np.argsort(indices, kind="stable")
    counts = np.concatenate([r.counts for r in records])
    starts = np.cumsum(counts) - counts
    # each run's instant rows, the runs in their new order
    rows = np.repeat(starts[order] - np.cumsum(np.append(0, counts[order][:-1])), counts[order]) \
        + np.arange(counts.sum())

    def cat(parts):
        return np.concatenate(parts)

    place = dict(zip(indices[order].tolist(), range(indices.size)))  # a run's index -> its place in the record

    first = records[0]
    return Record(
        indices[order], {key: cat([r.values[key] for r in records])[order] for key in first.values},
        extras={key: (units, cat([r.extras[key][1] for r in records])[order]) for key, (units, _) in first.extras.items()},
        series={name: (units, text, cat([r.series[name][2] for r in records])[order])
                for name, (units, text, _) in first.series.items()},
        counts=counts[order], instants={name: cat([r.instants[name] for r in records])[rows] for name in first.instants},
        after={name: cat([r.after[name] for r in records])[rows] for name in first.after},
        periodic={int(place[r.indices[k]]): periodic for r in records for k, periodic in r.periodic.items()}
        if any(r.periodic for r in records) else {})


def store_record(f: h5py.Group, record: Record) -> None:
    """``record`` kept in an HDF5 group (a streamed sweep's chunk file)."""
    f["indices"] = record.indices
    f.attrs["columns"] = json.dumps(list(record.values))
    for key, values in record.values.items():
        f[f"values/{key}"] = values
    if record.counts is None:
        return
    for key, (units, values) in record.extras.items():
        f[f"extras/{key}"] = values
        f[f"extras/{key}"].attrs["units"] = units
    for name, (units, text, block) in record.series.items():
        f[f"series/{name}"] = block
        f[f"series/{name}"].attrs["units"] = units
        f[f"series/{name}"].attrs["long_name"] = text
    f["instants/counts"] = record.counts
    for name, values in record.instants.items():
        if name in TEXT_COLUMNS:
            f.create_dataset(f"instants/{name}", data=values, dtype=TEXT)
        else:
            f[f"instants/{name}"] = values
    for name, values in record.after.items():
        f[f"after/{name}"] = values
    for k, periodic in record.periodic.items():
        write_periodic(f.create_group(f"periodic/{k}"), periodic)


def read_record(f: h5py.Group) -> Record:
    """The record kept in ``f`` by :func:`store_record` (its periodic regimes left in the file, to be copied)."""
    values = {key: f[f"values/{key}"][()] for key in json.loads(f.attrs["columns"])}
    record = Record(f["indices"][()], values)
    if "instants" not in f:
        return record
    record.extras = {key: (str(item.attrs["units"]), item[()]) for key, item in f.get("extras", {}).items()}
    record.series = {name: (str(item.attrs["units"]), str(item.attrs["long_name"]), item[()])
                     for name, item in f.get("series", {}).items()}
    record.counts = f["instants/counts"][()]
    record.instants = {name: f[f"instants/{name}"].asstr()[()].astype(object) if name in TEXT_COLUMNS
                       else f[f"instants/{name}"][()] for name in INSTANT_COLUMNS}
    record.after = {name: item[()] for name, item in f["after"].items()}
    record.periodic = {int(k): part for k, part in f.get("periodic", {}).items()}
    return record


def write_periodic(group: h5py.Group, periodic) -> None:
    """A run's periodic regime: its periods and, where it was analysed, Tredgold's diagram."""
    write_periods(group.create_group("periods"), periodic.regime)
    if periodic.diagram is not None:
        write_diagram(group.create_group("turning_moment"), periodic.diagram)


def summary_values(summaries: Summaries) -> dict[str, np.ndarray]:
    """The runs' summary values as the file keeps them, a column a value: floats, else integers (a yes/no
    too); the label apart."""
    columns = {}
    for key, values in summaries.columns.items():
        if key != "label":
            values = np.asarray(values)
            columns[key] = values.astype("f8" if values.dtype.kind == "f" else "i8")
    return columns


def series_blocks(runs, time, padded: bool) -> dict[str, np.ndarray]:
    """Every series of the runs on (run, time): each run's output-grid rows, NaN where a run has no row
    (a flag stays a small integer where every run has every row)."""
    blocks = {}
    places = [np.searchsorted(time, run.grid) for run in runs]
    rows = [run.grid_rows() for run in runs]
    for name, first in runs[0].series.items():
        dtype = np.float64 if padded or first.dtype.kind == "f" else first.dtype
        block = np.full((len(runs), time.size), np.nan if dtype == np.float64 else 0, dtype=dtype)
        for k, run in enumerate(runs):
            block[k, places[k]] = run.series[name][rows[k]]
        blocks[name] = block
    return blocks


def _run_extras(runs) -> dict:
    """Per-run numbers beside the summary: the energy ledger's terms and the solver's counts."""
    from ..machine.core.ledger import balance_columns
    from .run_summaries import ledger_columns

    extras = {}
    for key, values in balance_columns(ledger_columns(runs)).items():  # every run's ledger closed at once
        extras[f"energy_{key}"] = ("1" if key.endswith("relative_residual") else "J", np.asarray(values, dtype=float))
    for key in runs[0].stats:
        extras[f"solver_{key}"] = ("s" if key == "wall_time" else "1",
                                   np.asarray([run.stats[key] for run in runs]))
    return extras

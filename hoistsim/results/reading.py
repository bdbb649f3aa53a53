"""Reading results files back: format 2 (runs stacked), and format 1 (a group per run) as written before.

``open_results`` gives the Dataset xarray users work with; ``read_runs`` and
``read_summary`` give the plain per-run numbers the figures and tables use.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from functools import cached_property
from pathlib import Path

import h5py
import numpy as np

from .summaries import Summaries


def _version(f: h5py.File) -> int:
    return int(f.attrs.get("format_version", 1))


def read_runs(path, columns=None, attributes=None) -> list[dict]:
    """Read the runs of a file back as dicts of numpy arrays (for plots and tables), one per run.

    Each has ``time`` and its series on the output grid with the exact instants
    merged in (the state just after each), ``events`` (every instant: time,
    kind, element, torque_margin, mode_after, category), ``attrs`` (name,
    label, parameters and the run's summary values) and, for a periodic
    regime, ``periods`` and ``turning_moment``.  ``columns``: the series to read
    (all when None); ``attributes``: the summary values to keep past the first
    run (all when None).
    """
    with h5py.File(path, "r") as f:
        if _version(f) == 1:
            return _read_runs_v1(f, columns, attributes)
        if "runs" not in f or "time" not in f["runs"]:
            return []  # summaries only
        group = f["runs"]
        time = group["time"][()]
        series = [n for n, item in group.items() if isinstance(item, h5py.Dataset) and item.ndim == 2]
        wanted = [n for n in series if columns is None or n in columns]
        data = {name: group[name][()] for name in wanted}
        rows = next((data[n] for n in wanted if data[n].dtype.kind == "f"), None)
        if rows is None and series:
            rows = group[series[0]][()].astype(float)
        events = group["events"]
        owner = events["run"][()]
        instants = {name: events[name].asstr()[()] if events[name].dtype.kind == "O" else events[name][()]
                    for name in ("time", "kind", "element", "torque_margin", "mode_after", "category")}
        after = {name: events[name][()] for name in wanted}
        summary = _run_variables(group)
        base = {"name": group.attrs["name"], "parameters": group.attrs["parameters"]}
        runs = []
        for i in range(group["run"].shape[0]):
            on_grid = np.isfinite(rows[i]) if rows is not None else np.ones(time.size, bool)
            mine = owner == i
            run = merged_rows(time[on_grid], {name: data[name][i][on_grid] for name in wanted},
                              instants["time"][mine], {name: after[name][mine] for name in wanted})
            run["events"] = events_table({name: values[mine] for name, values in instants.items()})
            keys = summary if i == 0 or attributes is None else [k for k in attributes if k in summary]
            run["attrs"] = {**base, **{k: summary[k][i] for k in keys}}
            if f"periodic/{i}" in f:
                for name, part in f[f"periodic/{i}"].items():
                    run[name] = {k: v[()] for k, v in part.items()}
                    run[name]["attrs"] = dict(part.attrs)
            runs.append(run)
    return runs


def merged_rows(grid_time, on_grid: dict, instant_time, after: dict) -> dict[str, np.ndarray]:
    """A run's series on its output grid with the state just after each exact instant put in, in time order
    (an instant on a grid time: its row), and ``time``."""
    times = np.concatenate([grid_time, instant_time])
    order = np.argsort(times, kind="stable")
    sorted_times = times[order]
    keep = np.append(sorted_times[1:] != sorted_times[:-1], True)
    run = {name: np.concatenate([on_grid[name], after[name]])[order][keep] for name in on_grid}
    run["time"] = sorted_times[keep]
    return run


_EVENT_FIELDS = [("time", "f8"), ("kind", object), ("element", object), ("torque_margin", "f8"),
                 ("mode_after", object), ("category", object)]


def events_table(instants: dict) -> np.ndarray:
    """A run's instants as one table (a row an instant): time, kind, element, torque_margin, mode_after,
    category."""
    table = np.zeros(len(instants["time"]), dtype=_EVENT_FIELDS)
    for name in table.dtype.names:
        table[name] = instants[name]
    return table


def _run_variables(group: h5py.Group) -> dict[str, np.ndarray]:
    """The (run) variables named in ``summary_columns``: label, swept keys, summary values."""
    out = {}
    for name in json.loads(group.attrs["summary_columns"]):
        item = group[name]
        out[name] = item.asstr()[()] if item.dtype.kind == "O" else item[()]
    return out


def read_swept_keys(path) -> list[str]:
    with h5py.File(path, "r") as f:
        holder = f["summary"] if _version(f) == 1 else f["runs"]
        return json.loads(holder.attrs.get("swept_keys", "[]"))


def read_summary_units(path) -> dict[str, str]:
    """Each summary column's units (the swept keys' are SI; "" where none is recorded)."""
    with h5py.File(path, "r") as f:
        if _version(f) == 1:
            text = f["summary"].attrs.get("units", "")
            text = text.decode() if isinstance(text, bytes) else str(text)
            return dict(item.split(": ", 1) for item in text.split(", ") if ": " in item)
        group = f["runs"]
        return {name: str(group[name].attrs.get("units", "")) for name in json.loads(group.attrs["summary_columns"])
                if name != "label"}


def read_summary(path) -> list[dict]:
    """Every run's label, swept values and summary as one dict per run (plain Python values)."""
    with h5py.File(path, "r") as f:
        if _version(f) == 1:
            table = f["summary"][()]
            columns = {name: table[name] for name in table.dtype.names}
        else:
            columns = _run_variables(f["runs"])
    names = list(columns)
    lists = [np.asarray(columns[n]).tolist() for n in names]
    return [{n: (v.decode() if isinstance(v, bytes) else v) for n, v in zip(names, values)} for values in zip(*lists)]


class FileSummaries(Sequence):
    """The summaries of a results file's runs (format 2), read when asked for: a dict per run by index,
    as :class:`hoistsim.results.run_result.Summaries`, or every ``columns``.  A streamed sweep of a million runs
    returns these: its memory does not grow with the runs it keeps."""

    def __init__(self, path, flags=()):
        self.path, self.flags = Path(path), set(flags)  # flags: yes/no values, stored as 0/1
        with h5py.File(self.path, "r") as f:
            group = f["runs"]
            swept = set(json.loads(group.attrs["swept_keys"]))
            self.names = [n for n in json.loads(group.attrs["summary_columns"]) if n not in swept]
            self.count = int(group["run"].shape[0])

    def __len__(self) -> int:
        return self.count

    def _read(self, rows: slice) -> Summaries:
        with h5py.File(self.path, "r") as f:
            group = f["runs"]
            columns = {name: group[name].asstr()[rows] if name == "label" else group[name][rows]
                       for name in self.names}
        return Summaries({name: values.astype(object) if name == "label" else
                          values.astype(bool) if name in self.flags else values for name, values in columns.items()})

    def __getitem__(self, index):
        if isinstance(index, slice):
            start, stop, step = index.indices(self.count)
            return self._read(slice(start, stop))[::step] if stop > start else []
        if index < 0:
            index += self.count
        if not 0 <= index < self.count:
            raise IndexError(index)
        return self._read(slice(index, index + 1))[0]

    @cached_property
    def columns(self) -> dict[str, np.ndarray]:
        return self._read(slice(None)).columns


def open_results(path):
    """A results file's runs as one xarray.Dataset: (run, time) series, (run) swept keys and summaries.

    The exact instants are ``xarray.open_dataset(path, group="runs/events", engine="h5netcdf")``.
    """
    import xarray as xr

    return xr.open_dataset(path, group="runs", engine="h5netcdf")


def _read_runs_v1(f: h5py.File, columns, attributes) -> list[dict]:
    """Format 1 (one group a run), as files written before format 2."""
    runs = []
    for index, key in enumerate(sorted(f.get("runs", {}), key=int)):
        group = f["runs"][key]
        names = set(group)
        wanted = names - {"events", "event"} if columns is None else names & set(columns)
        run = {name: group[name][()] for name in wanted if isinstance(group[name], h5py.Dataset)}
        for name in names & {"periods", "turning_moment"}:
            run[name] = {k: v[()] for k, v in group[name].items()}
            run[name]["attrs"] = dict(group[name].attrs)
        run["events"] = group["events"][()]
        keep = None if index == 0 or attributes is None else attributes
        run["attrs"] = {k: group.attrs[k] for k in (group.attrs if keep is None else keep) if k in group.attrs}
        runs.append(run)
    return runs

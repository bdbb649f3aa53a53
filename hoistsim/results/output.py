"""HDF5 output, format 2, written atomically: a file is complete or absent.

Runs arrive as *records* (:mod:`.records`: a block's summaries, series blocks
and instants) and :func:`assemble` builds the file from them one at a time, so
one run written at once (one record, handed over in memory) and a sweep streamed
as its chunks finish (records kept as files, :mod:`hoistsim.running.streaming`)
take the same path.  Reading is :mod:`hoistsim.results.reading`.

Format 2 (its names and units are docs/output.md), one layout for one run or a million:

    /runs          ``xarray.open_dataset(path, group="runs", engine="h5netcdf")`` is one Dataset:
                   run (run) and time (time, the output grid) dimension scales; every series on
                   (run, time), NaN where a run has no row; label, each swept key's SI value and
                   every summary value on (run); chunked along run and compressed
    /runs/events   every exact instant of every run on (event): run, time, kind, element,
                   category, torque_margin, mode_after, and each series just after it
    /periodic/<i>/ the periodic regime of run i: periods (a row a period) and turning_moment
    /scenario      the scenario text, with provenance attributes
"""

from __future__ import annotations

import datetime as _dt
import functools
import json
import platform
from dataclasses import dataclass

import h5py
import numpy as np

from .atomic import atomic_path
from .records import INSTANT_COLUMNS, TEXT, TEXT_COLUMNS, Record, make_record, store_record, write_periodic
from .summary_meanings import extra_meaning, summary_meaning


def provenance() -> dict[str, str]:
    return {"created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"), **_versions()}


@functools.lru_cache(maxsize=1)
def _versions() -> dict[str, str]:
    """Python's and the packages' versions: read once a process (each costs a scan of the installed packages,
    which ``hoistsim watch`` would pay at every save)."""
    from importlib.metadata import PackageNotFoundError, version

    info = {"python_version": platform.python_version()}
    for package in ("hoistsim", "jax", "diffrax", "numpy", "h5py"):
        try:
            info[f"{package}_version"] = version(package)
        except PackageNotFoundError:
            info[f"{package}_version"] = "unknown"
    return info


def write_runs(path, runs, *, command: str = "", parameters: dict | None = None) -> None:
    """Write runs (in sweep order) to ``path`` atomically: one record of them all, assembled."""
    if not runs:
        raise ValueError("no runs to write")
    _write_at_once(path, runs[0].scenario, [run.label or run.name for run in runs], parameters or {}, runs,
                   runs[0].summary_units, summary_only=False, command=command)


def write_sweep(path, result, *, command: str = "", units: dict[str, str] | None = None) -> None:
    """Write a sweep: every run's time series, or (summary-only) the run variables alone.  ``units``: the
    summary columns' (None: the scene's summaries')."""
    summary_only = result.runs is None
    _write_at_once(path, result.scenario, result.labels, result.parameters,
                   result.summaries if summary_only else result.runs, units or result.summary_units,
                   summary_only=summary_only, command=command)


def _write_at_once(path, scenario, labels, parameters, outcomes, units, *, summary_only: bool, command: str) -> None:
    time, padded = (None, False) if summary_only else common_time([run.grid for run in outcomes])
    record = make_record(range(len(outcomes)), outcomes, summary_only=summary_only, time=time, padded=padded)
    assemble(path, [record], Heading(scenario, labels, parameters, summary_only, time, units, command))


FORMAT_VERSION = 2
LABEL_SLICE = 65536  # labels made and written at a time


def _start_file(f: h5py.File, summary_only: bool) -> None:
    f.attrs["format"] = "hoistsim-runs"
    f.attrs["format_version"] = FORMAT_VERSION
    f.attrs["summary_only"] = summary_only


def _scale(group: h5py.Group, name: str, values, units: str, text: str):
    data = group.create_dataset(name, data=values)
    data.attrs["units"] = units
    data.attrs["long_name"] = text
    data.make_scale(name)
    return data


def _variable(group: h5py.Group, name: str, values, units: str, text: str, dims: tuple, **options):
    data = group.create_dataset(name, data=values, **options)
    data.attrs["units"] = units
    if text:
        data.attrs["long_name"] = text
    for axis, scale in enumerate(dims):
        data.dims[axis].attach_scale(scale)
    return data


def common_time(grids) -> tuple[np.ndarray, bool]:
    """The time axis every run's output grid lies on, and whether some run lacks some of its rows."""
    grids = [np.asarray(g) for g in grids]
    if all(g.shape == grids[0].shape and np.array_equal(g, grids[0]) for g in grids[1:]):
        return grids[0], False
    return np.unique(np.concatenate(grids)), True


# ------------------------------------------------------------------ records: runs as they finish

def write_record(f: h5py.Group, indices, outcomes, *, summary_only: bool, time, padded: bool) -> None:
    """Runs at ``indices`` (RunResults, or their :class:`hoistsim.results.run_result.Summaries` when summary-only,
    or their :class:`.records.Record` made already) kept in ``f`` as a record for :func:`assemble` (read back with
    :func:`.records.read_record`)."""
    store_record(f, outcomes if isinstance(outcomes, Record) else
                 make_record(indices, outcomes, summary_only=summary_only, time=time, padded=padded))


@dataclass
class Heading:
    """What a results file says of the whole sweep: its scenario, labels, swept values and time axis."""

    scenario: object
    labels: object  # a sequence of str (a sweep's are made when read)
    parameters: dict
    summary_only: bool
    time: np.ndarray | None
    summary_units: dict  # summary column -> units, as the scene's elements declare them (summary_units)
    command: str = ""


def assemble(path, records, layout: Heading) -> None:
    """The results file at ``path`` from records taken one at a time, written under a temporary name
    and moved into place: the (run) and (run, time) variables filled record by record (an HDF5 chunk a
    record, written once), the instants appended."""
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            Assembly(f, layout).build(records)


class Assembly:
    """Format 2 from records (see the module docstring)."""

    def __init__(self, f: h5py.File, layout: Heading):
        self.f, self.layout = f, layout
        self.count = len(layout.labels)
        self.instants = 0
        self.scales: dict[str, h5py.Dataset] = {}  # run, time: held, not looked up by name for every column
        self.columns: dict[str, h5py.Dataset] = {}

    def build(self, records) -> None:
        f, layout = self.f, self.layout
        _start_file(f, layout.summary_only)
        group = f.create_group("runs")
        run = self.scales["run"] = _scale(group, "run", np.arange(self.count), "1", "run index, in sweep order")
        labels = _variable(group, "label", None, "1", "the run's swept values (or the scenario's name)", (run,),
                           shape=(self.count,), dtype=TEXT)
        for start in range(0, self.count, LABEL_SLICE):  # a slice at a time: a million never all at once
            labels[start:start + LABEL_SLICE] = np.asarray(layout.labels[start:start + LABEL_SLICE], dtype=object)
        from ..scenario.keys import key_units

        for key, values in layout.parameters.items():
            _variable(group, key, np.asarray(values, dtype=float), key_units(key), f"swept: {key} (SI)", (run,))
        if layout.time is not None:
            self.scales["time"] = _scale(group, "time", layout.time, "s",
                                         "time since the start (the output grid; exact instants are in events)")
        units = layout.summary_units
        columns = None
        for record in records:  # one at a time (a streamed sweep's read from its chunk file as it comes)
            columns = columns or list(record.values)
            self._record(group, record, units)
        group.attrs["summary_columns"] = json.dumps(["label", *layout.parameters, *(columns or [])])
        group.attrs["swept_keys"] = json.dumps(list(layout.parameters))
        group.attrs["name"] = layout.scenario.name
        group.attrs["parameters"] = json.dumps(layout.scenario.resolved(), sort_keys=True)
        sim = layout.scenario.simulation
        group.attrs["solver"], group.attrs["rtol"], group.attrs["atol"] = sim.solver, sim.rtol, sim.atol
        _write_scenario(f, layout.scenario, layout.command)

    def _put(self, group, name, values, rows, units, text="", time_axis=False, comment="") -> None:
        """A record's values of one column into its rows of the file, the column made at its first record;
        ``comment``: what its 0 or NaN stand for, where they stand for something."""
        if name in self.columns:
            self.columns[name][rows] = values
            return
        whole = rows == slice(0, self.count)  # one record holds every run: the column is written as it is made
        shape = (self.count, self.scales["time"].shape[0]) if time_axis else (self.count,)
        options = {}
        if time_axis:  # an HDF5 chunk a record: each is written once, never read back and rewritten
            options = dict(chunks=(min(self.count, len(values)), shape[1]), compression="gzip", compression_opts=1,
                           shuffle=True)
        data = group.create_dataset(name, shape=shape, dtype=values.dtype, data=values if whole else None,
                                    fillvalue=np.nan if values.dtype.kind == "f" else 0, **options)
        data.attrs["units"] = units
        if text:
            data.attrs["long_name"] = text
        if comment:
            data.attrs["comment"] = comment
        data.dims[0].attach_scale(self.scales["run"])
        if time_axis:
            data.dims[1].attach_scale(self.scales["time"])
        self.columns[name] = data
        if not whole:
            data[rows] = values

    def _record(self, group, record: Record, units) -> None:
        indices = record.indices
        contiguous = indices[-1] - indices[0] + 1 == len(indices)
        rows = slice(int(indices[0]), int(indices[-1]) + 1) if contiguous else indices
        for key, values in record.values.items():  # the summary, each in words
            text, comment = summary_meaning(key)
            self._put(group, key, values, rows, units.get(key, ""), text, comment=comment)
        for key, (unit, values) in record.extras.items():
            if key not in record.values:  # the residuals are summary values already
                self._put(group, key, values, rows, unit, extra_meaning(key))
        for name, (unit, text, block) in record.series.items():
            self._put(group, name, block, rows, unit, text, time_axis=True)
        if record.counts is not None:
            self._instants(group, record, indices)
        for k, periodic in record.periodic.items():
            name = str(int(indices[k]))
            if isinstance(periodic, h5py.Group):  # kept in a chunk file: copied as it is
                self.f.copy(periodic, self.f.require_group("periodic"), name=name)
            else:
                write_periodic(self.f.require_group("periodic").create_group(name), periodic)

    def _instants(self, group, record, indices) -> None:
        events = group.require_group("events")
        counts = record.counts
        columns = {"run": np.repeat(indices, counts).astype(np.int64), **record.instants, **record.after}
        added, start = int(counts.sum()), self.instants
        self.instants += added
        if "event" in events:  # appended to the rows of the records before
            for name, values in {"event": np.arange(start, start + added), **columns}.items():
                data = events[name]
                data.resize((start + added,))
                data[start:] = values
            return
        # the first record makes the columns, with its rows in them
        scale = events.create_dataset("event", data=np.arange(added, dtype=np.int64), maxshape=(None,), chunks=(4096,))
        scale.attrs["units"] = "1"
        scale.attrs["long_name"] = "instant index, runs in order"
        scale.make_scale("event")
        texts = {"run": ("1", "the run it belongs to"), **INSTANT_COLUMNS}
        for name, values in columns.items():
            units, text = texts[name] if name in texts else (str(self.columns[name].attrs["units"]),
                                                             "value just after the instant")
            data = events.create_dataset(name, data=values, maxshape=(None,), chunks=(4096,),
                                         dtype=TEXT if name in TEXT_COLUMNS else values.dtype)
            data.attrs["units"] = units
            data.attrs["long_name"] = text
            data.dims[0].attach_scale(scale)


# Summary columns the host adds to the elements' own (which declare their units).
_HOST_SUMMARY_UNITS = {"lock_events": "1", "unlock_events": "1", "energy_residual": "J",
                       "energy_relative_residual": "1", "heat_relative_residual": "1"}


def summary_units(layout) -> dict[str, str]:
    """Units of every summary column of a machine (its :class:`hoistsim.machine.core.layout.Layout`): as its
    elements declare them, yes/no values as 1, and the host's own."""
    from .periodic.analysis import periodic_summary_units

    declared = {**layout.summaries, **periodic_summary_units(layout)}
    return {**{k: "1" if u == "bool" else u for k, u in declared.items()}, **_HOST_SUMMARY_UNITS}


def _write_scenario(f: h5py.File, scenario, command: str) -> None:
    data = f.create_dataset("scenario", data=scenario.text, dtype=TEXT)
    data.attrs["units"] = "1"
    data.attrs["source"] = scenario.source
    data.attrs["command"] = command
    data.attrs["solver"] = scenario.simulation.solver
    data.attrs["rtol"] = scenario.simulation.rtol
    data.attrs["atol"] = scenario.simulation.atol
    for key, value in provenance().items():
        data.attrs[key] = value

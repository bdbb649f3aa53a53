"""HDF5 output, format 2, written atomically: a file is complete or absent.

Runs arrive as *records* (:func:`write_record`: a chunk's summaries, series
blocks and instants) and :func:`assemble` builds the file from them one at a
time, so one run written at once (one record in memory) and a sweep streamed
as its chunks finish (records kept as files, :mod:`hoistsim.running.streaming`) take
the same path.  Reading is :mod:`hoistsim.results.reading`.

Format 2 (the contract's names; see README), one layout for one run or a million:

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
from .output_periodic import write_diagram, write_periods
from .summaries import Summaries

_TEXT = h5py.string_dtype()


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
                   summary_only=False, command=command)


def write_sweep(path, result, *, command: str = "") -> None:
    """Write a sweep: every run's time series, or (summary-only) the run variables alone."""
    summary_only = result.runs is None
    _write_at_once(path, result.scenario, result.labels, result.parameters,
                   result.summaries if summary_only else result.runs, summary_only=summary_only, command=command)


def _write_at_once(path, scenario, labels, parameters, outcomes, *, summary_only: bool, command: str) -> None:
    time, padded = (None, False) if summary_only else common_time([run.grid for run in outcomes])
    with h5py.File(f"record-{id(outcomes)}", "w", driver="core", backing_store=False) as record:
        write_record(record, range(len(outcomes)), outcomes, summary_only=summary_only, time=time, padded=padded)
        assemble(path, [record], Heading(scenario, labels, parameters, summary_only, time, command))


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


def _run_extras(runs) -> dict:
    """Per-run numbers beside the summary: the energy ledger's terms and the solver's counts."""
    extras = {}
    balances = [run.energy_balance for run in runs]  # each closes the run's ledger: once a run
    for key in balances[0]:
        extras[f"energy_{key}"] = ("1" if key.endswith("relative_residual") else "J",
                                   np.asarray([balance[key] for balance in balances], dtype=float))
    for key in runs[0].stats:
        extras[f"solver_{key}"] = ("s" if key == "wall_time" else "1",
                                   np.asarray([run.stats[key] for run in runs]))
    return extras


def common_time(grids) -> tuple[np.ndarray, bool]:
    """The time axis every run's output grid lies on, and whether some run lacks some of its rows."""
    grids = [np.asarray(g) for g in grids]
    if all(g.shape == grids[0].shape and np.array_equal(g, grids[0]) for g in grids[1:]):
        return grids[0], False
    return np.unique(np.concatenate(grids)), True


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


# ------------------------------------------------------------------ records: runs as they finish

# What an instant row holds besides the series just after it, with its units and meaning.
_INSTANT_COLUMNS = {
    "time": ("s", "the instant, exact (root-found or scheduled)"),
    "kind": ("1", "lock, unlock, reversal, engage, disengage, a scheduled event, an observation "
                  "(slip_peak, load_lowest, ...) or a period mark"),
    "element": ("1", "the element it belongs to"),
    "category": ("1", "switch, scheduled, observation or cycle"),
    "torque_margin": ("N*m", "the coupling's static capacity minus the torque it would carry stuck "
                             "(NaN where it does not apply)"),
    "mode_after": ("1", "the coupling's mode after it"),
}
_TEXT_COLUMNS = ("kind", "element", "category", "mode_after")


def write_record(f: h5py.Group, indices, outcomes, *, summary_only: bool, time, padded: bool) -> None:
    """Runs at ``indices`` (RunResults, or their :class:`hoistsim.results.run_result.Summaries` when summary-only) as a
    record for :func:`assemble`."""
    f["indices"] = np.asarray(list(indices), dtype=np.int64)
    summaries = summary_values(outcomes if summary_only else Summaries.from_rows([o.summary for o in outcomes]))
    f.attrs["columns"] = json.dumps(list(summaries))
    for key, values in summaries.items():
        f[f"values/{key}"] = values
    if summary_only:
        return
    runs = outcomes
    for key, (units, values) in _run_extras(runs).items():
        f[f"extras/{key}"] = values
        f[f"extras/{key}"].attrs["units"] = units
    first = runs[0]
    for name, block in series_blocks(runs, time, padded).items():
        f[f"series/{name}"] = block
        f[f"series/{name}"].attrs["units"] = first.units[name]
        f[f"series/{name}"].attrs["long_name"] = first.descriptions.get(name, "")
    tables = [run.instants for run in runs]
    f["instants/counts"] = np.asarray([len(t["time"]) for t in tables], dtype=np.int64)
    for name in _INSTANT_COLUMNS:
        values = np.concatenate([np.asarray(t[name]) for t in tables])
        if name in _TEXT_COLUMNS:
            f.create_dataset(f"instants/{name}", data=values.astype(object), dtype=_TEXT)
        else:
            f[f"instants/{name}"] = values.astype(float)
    for name in first.series:
        f[f"after/{name}"] = np.concatenate([run.series[name][run.instant_rows()] for run in runs])
    for k, run in enumerate(runs):
        if run.periodic is not None:
            group = f.create_group(f"periodic/{k}")
            write_periods(group.create_group("periods"), run.periodic.regime)
            if run.periodic.diagram is not None:
                write_diagram(group.create_group("turning_moment"), run.periodic.diagram)


def summary_values(summaries: Summaries) -> dict[str, np.ndarray]:
    """The runs' summary values as the file keeps them, a column a value: floats, else integers (a yes/no
    too); the label apart."""
    columns = {}
    for key, values in summaries.columns.items():
        if key != "label":
            values = np.asarray(values)
            columns[key] = values.astype("f8" if values.dtype.kind == "f" else "i8")
    return columns


@dataclass
class Heading:
    """What a results file says of the whole sweep: its scenario, labels, swept values and time axis."""

    scenario: object
    labels: object  # a sequence of str (a sweep's are made when read)
    parameters: dict
    summary_only: bool
    time: np.ndarray | None
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
                           shape=(self.count,), dtype=_TEXT)
        for start in range(0, self.count, LABEL_SLICE):  # a slice at a time: a million never all at once
            labels[start:start + LABEL_SLICE] = np.asarray(layout.labels[start:start + LABEL_SLICE], dtype=object)
        from ..scenario.keys import key_units

        for key, values in layout.parameters.items():
            _variable(group, key, np.asarray(values, dtype=float), key_units(key), f"swept: {key} (SI)", (run,))
        if layout.time is not None:
            self.scales["time"] = _scale(group, "time", layout.time, "s",
                                         "time since the start (the output grid; exact instants are in events)")
        units = _summary_units(layout.scenario)
        columns = None
        for record in records:  # open HDF5 groups, one at a time
            columns = columns or json.loads(record.attrs["columns"])
            self._record(group, record, units)
        group.attrs["summary_columns"] = json.dumps(["label", *layout.parameters, *(columns or [])])
        group.attrs["swept_keys"] = json.dumps(list(layout.parameters))
        group.attrs["name"] = layout.scenario.name
        group.attrs["parameters"] = json.dumps(layout.scenario.resolved(), sort_keys=True)
        sim = layout.scenario.simulation
        group.attrs["solver"], group.attrs["rtol"], group.attrs["atol"] = sim.solver, sim.rtol, sim.atol
        _write_scenario(f, layout.scenario, layout.command)

    def _put(self, group, name, values, rows, units, text="", time_axis=False) -> None:
        """A record's values of one column into its rows of the file, the column made at its first record."""
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
        data.dims[0].attach_scale(self.scales["run"])
        if time_axis:
            data.dims[1].attach_scale(self.scales["time"])
        self.columns[name] = data
        if not whole:
            data[rows] = values

    def _record(self, group, record, units) -> None:
        indices = record["indices"][()]
        contiguous = indices[-1] - indices[0] + 1 == len(indices)
        rows = slice(int(indices[0]), int(indices[-1]) + 1) if contiguous else indices
        summaries = record["values"]
        for key, item in summaries.items():
            self._put(group, key, item[()], rows, units.get(key, ""))
        for key, item in record.get("extras", {}).items():
            if key not in summaries:  # the residuals are summary values already
                self._put(group, key, item[()], rows, str(item.attrs["units"]))
        for name, item in record.get("series", {}).items():
            self._put(group, name, item[()], rows, str(item.attrs["units"]), str(item.attrs["long_name"]),
                      time_axis=True)
        if "instants" in record:
            self._instants(group, record, indices)
        for key, part in record.get("periodic", {}).items():
            self.f.copy(part, self.f.require_group("periodic"), name=str(int(indices[int(key)])))

    def _instants(self, group, record, indices) -> None:
        events = group.require_group("events")
        counts = record["instants/counts"][()]
        columns = {"run": np.repeat(indices, counts).astype(np.int64)}
        for name in _INSTANT_COLUMNS:
            item = record[f"instants/{name}"]
            columns[name] = item.asstr()[()].astype(object) if name in _TEXT_COLUMNS else item[()]
        columns.update({name: item[()] for name, item in record["after"].items()})
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
        texts = {"run": ("1", "the run it belongs to"), **_INSTANT_COLUMNS}
        for name, values in columns.items():
            units, text = texts[name] if name in texts else (str(self.columns[name].attrs["units"]),
                                                             "value just after the instant")
            data = events.create_dataset(name, data=values, maxshape=(None,), chunks=(4096,),
                                         dtype=_TEXT if name in _TEXT_COLUMNS else values.dtype)
            data.attrs["units"] = units
            data.attrs["long_name"] = text
            data.dims[0].attach_scale(scale)


# Summary columns the host adds to the elements' own (which declare their units).
_HOST_SUMMARY_UNITS = {"lock_events": "1", "unlock_events": "1", "energy_residual": "J",
                       "energy_relative_residual": "1", "heat_relative_residual": "1"}


def _summary_units(scenario) -> dict[str, str]:
    """Units of every summary column: as the scene's elements declare them, yes/no values as 1."""
    from ..machine.assemble import machine_elements
    from ..machine.core.layout import Layout
    from .periodic.analysis import summary_units

    layout = Layout(machine_elements(scenario))
    declared = {**layout.summaries, **summary_units(layout)}
    return {**{k: "1" if u == "bool" else u for k, u in declared.items()}, **_HOST_SUMMARY_UNITS}


def _write_scenario(f: h5py.File, scenario, command: str) -> None:
    data = f.create_dataset("scenario", data=scenario.text, dtype=_TEXT)
    data.attrs["units"] = "1"
    data.attrs["source"] = scenario.source
    data.attrs["command"] = command
    data.attrs["solver"] = scenario.simulation.solver
    data.attrs["rtol"] = scenario.simulation.rtol
    data.attrs["atol"] = scenario.simulation.atol
    for key, value in provenance().items():
        data.attrs[key] = value

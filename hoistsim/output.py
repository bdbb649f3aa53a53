"""HDF5 output, written atomically: a file is complete or absent.

Format 2 (the contract's names; see README), one layout for one run or a million:

    /runs          ``xarray.open_dataset(path, group="runs", engine="h5netcdf")`` is one Dataset:
                   run (run) and time (time, the output grid) dimension scales; every series on
                   (run, time), NaN where a run has no row; label, each swept key's SI value and
                   every summary value on (run); chunked along run and compressed
    /runs/events   every exact instant of every run on (event): run, time, kind, element,
                   category, torque_margin, mode_after, and each series just after it
    /periodic/<i>/ the periodic regime of run i: periods (a row a period) and turning_moment
    /scenario      the scenario text, with provenance attributes

Format 1 files (a group per run, /summary) are still read.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import json
import os
import platform
import tempfile
from pathlib import Path

import h5py
import numpy as np

_TEXT = h5py.string_dtype()


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; move it into place only if the block succeeds.

    A failure, an exception or a killed process leaves any existing file at
    ``path`` untouched (at worst a stray hidden temporary file remains).
    """
    target = Path(path)
    directory = target.parent if str(target.parent) else Path(".")
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".partial", dir=directory)
    os.close(fd)
    try:
        yield Path(tmp)
        with open(tmp, "rb+") as handle:  # make the bytes durable before they take the name
            os.fsync(handle.fileno())
        # mkstemp creates the file readable by its owner alone; a results file is for colleagues
        # too, as any file this user creates: the mode the umask allows
        os.chmod(tmp, 0o666 & ~_umask())
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _umask() -> int:
    mask = os.umask(0)  # the only way to read it is to set it: put it straight back
    os.umask(mask)
    return mask


def provenance() -> dict[str, str]:
    from importlib.metadata import PackageNotFoundError, version

    info = {
        "created": _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds"),
        "python_version": platform.python_version(),
    }
    for package in ("hoistsim", "jax", "diffrax", "numpy", "h5py"):
        try:
            info[f"{package}_version"] = version(package)
        except PackageNotFoundError:
            info[f"{package}_version"] = "unknown"
    return info


def write_runs(path, runs, *, command: str = "", parameters: dict | None = None) -> None:
    """Write runs (in sweep order) to ``path`` atomically, stacked (format 2)."""
    if not runs:
        raise ValueError("no runs to write")
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            _start_file(f, summary_only=False)
            group = f.create_group("runs")
            _write_run_variables(group, [run.summary for run in runs], parameters or {},
                                 _summary_units(runs[0].scenario), runs[0].scenario,
                                 extra=_run_extras(runs))
            _write_series(group, runs)
            _write_instants(group.create_group("events"), runs)
            for index, run in enumerate(runs):
                if run.periodic is not None:
                    periodic = f.create_group(f"periodic/{index}")
                    _write_periods(periodic.create_group("periods"), run.periodic.regime)
                    if run.periodic.diagram is not None:
                        _write_diagram(periodic.create_group("turning_moment"), run.periodic.diagram)
            _write_scenario(f, runs[0].scenario, command)


def write_sweep(path, result, *, command: str = "") -> None:
    """Write a sweep: every run's time series, or (summary-only) the run variables alone."""
    if result.runs is not None:
        write_runs(path, result.runs, command=command, parameters=result.parameters)
        return
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            _start_file(f, summary_only=True)
            _write_run_variables(f.create_group("runs"), result.summaries, result.parameters,
                                 _summary_units(result.scenario), result.scenario)
            _write_scenario(f, result.scenario, command)


FORMAT_VERSION = 2


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
    for key in runs[0].energy_balance:
        extras[f"energy_{key}"] = ("J" if key != "relative_residual" else "1",
                                   np.asarray([run.energy_balance[key] for run in runs], dtype=float))
    for key in runs[0].stats:
        extras[f"solver_{key}"] = ("s" if key == "wall_time" else "1",
                                   np.asarray([run.stats[key] for run in runs]))
    return extras


def _write_run_variables(group: h5py.Group, rows: list[dict], parameters: dict, units: dict[str, str],
                         scenario, extra: dict | None = None) -> None:
    """The (run) variables: label, each swept key's SI value (NaN for tables), every summary column."""
    from .scenario import key_units

    run = _scale(group, "run", np.arange(len(rows)), "1", "run index, in sweep order")
    _variable(group, "label", np.asarray([row["label"] for row in rows], dtype=object), "1",
              "the run's swept values (or the scenario's name)", (run,), dtype=_TEXT)
    for key, values in parameters.items():
        _variable(group, key, np.asarray(values, dtype=float), key_units(key), f"swept: {key} (SI)", (run,))
    columns = [k for k in rows[0] if k != "label"]
    for key in columns:
        kind = "f8" if isinstance(rows[0][key], float) else "i8"
        _variable(group, key, np.asarray([row[key] for row in rows], dtype=kind), units.get(key, ""), "", (run,))
    for key, (unit, values) in (extra or {}).items():
        if key not in group:  # the residuals are summary columns already
            _variable(group, key, values, unit, "", (run,))
    group.attrs["swept_keys"] = json.dumps(list(parameters))
    group.attrs["summary_columns"] = json.dumps(["label", *parameters, *columns])
    group.attrs["name"] = scenario.name
    group.attrs["parameters"] = json.dumps(scenario.resolved(), sort_keys=True)
    sim = scenario.simulation
    group.attrs["solver"], group.attrs["rtol"], group.attrs["atol"] = sim.solver, sim.rtol, sim.atol


def _common_grid(runs) -> tuple[np.ndarray, list]:
    """The time axis every run's grid lies on, and where each run's grid rows fall in it."""
    grids = [np.asarray(run.grid if run.grid is not None else run.time) for run in runs]
    if all(g.shape == grids[0].shape and np.array_equal(g, grids[0]) for g in grids[1:]):
        return grids[0], [slice(None)] * len(runs)
    union = np.unique(np.concatenate(grids))
    return union, [np.searchsorted(union, g) for g in grids]


def stacked_series(runs):
    """The common time axis and every series stacked (run, time): each run's output-grid rows, NaN where
    a run has no row (a flag column stays a small integer where every run has every row)."""
    time, places = _common_grid(runs)
    padded = any(not isinstance(p, slice) for p in places)
    rows = [run.grid_rows() for run in runs]
    stacked = {}
    for name, first in runs[0].series.items():
        dtype = np.float64 if padded or first.dtype.kind == "f" else first.dtype
        values = np.full((len(runs), time.size), np.nan if dtype == np.float64 else 0, dtype=dtype)
        for i, (run, place) in enumerate(zip(runs, places)):
            values[i, place] = run.series[name][rows[i]]
        stacked[name] = values
    return time, stacked


def _write_series(group: h5py.Group, runs) -> None:
    """Every series on (run, time), chunked along run and compressed."""
    time, stacked = stacked_series(runs)
    scale = _scale(group, "time", time, "s", "time since the start (the output grid; exact instants are in events)")
    first = runs[0]
    chunks = (min(len(runs), max(1, 2**18 // max(time.size, 1))), time.size)
    for name, values in stacked.items():
        _variable(group, name, values, first.units[name], first.descriptions.get(name, ""),
                  (group["run"], scale), chunks=chunks, compression="gzip", compression_opts=1, shuffle=True)


def _write_instants(group: h5py.Group, runs) -> None:
    """Every exact instant of every run, one row each, with the value of every series just after it."""
    tables = [run.all_instants() for run in runs]
    counts = [len(t["time"]) for t in tables]
    event = _scale(group, "event", np.arange(sum(counts)), "1", "instant index, runs in order")
    _variable(group, "run", np.repeat(np.arange(len(runs)), counts), "1", "the run it belongs to", (event,))
    texts = {"time": ("s", "the instant, exact (root-found or scheduled)"),
             "kind": ("1", "lock, unlock, reversal, engage, disengage, a scheduled event, an observation "
                           "(slip_peak, load_lowest, ...) or a period mark"),
             "element": ("1", "the element it belongs to"),
             "category": ("1", "switch, scheduled, observation or cycle"),
             "torque_margin": ("N*m", "the coupling's static capacity minus the torque it would carry stuck "
                                      "(NaN where it does not apply)"),
             "mode_after": ("1", "the coupling's mode after it")}
    for name, (units, text) in texts.items():
        values = np.concatenate([np.asarray(t[name]) for t in tables]) if counts else np.zeros(0)
        kind = dict(dtype=_TEXT) if name in ("kind", "element", "category", "mode_after") else {}
        _variable(group, name, values.astype(object) if kind else values.astype(float), units, text, (event,),
                  **kind)
    first = runs[0]
    for name in first.series:
        values = np.concatenate([run.series[name][run.instant_rows()] for run in runs]) if counts else np.zeros(0)
        _variable(group, name, values, first.units[name], "value just after the instant", (event,))


def _write_diagram(group: h5py.Group, diagram) -> None:
    """Tredgold's turning-moment diagram of the analysed regime, on the dimension ``angle``."""
    angle = group.create_dataset("angle", data=diagram.angle)
    angle.attrs["units"] = "rad"
    angle.attrs["long_name"] = "motor angle from the start of the first analysed period"
    angle.make_scale("angle")
    for name, values, units, text in (
            ("driving_torque", diagram.driving, "N*m", "driving torque M'_m at the motor shaft, at the mean speed"),
            ("resisting_torque", diagram.resisting, "N*m",
             "resisting torque M'_r at the motor shaft (inertia torques of reciprocating parts at the mean speed)"),
            ("energy", diagram.energy, "J", "integral of (M'_m - M'_r) over the angle from the period's start")):
        data = group.create_dataset(name, data=values)
        data.attrs["units"] = units
        data.attrs["long_name"] = text
        data.dims[0].attach_scale(angle)
    for key in ("mean_speed", "inertia", "energy_fluctuation", "min_speed_angle", "max_speed_angle",
                "work_residual", "irregularity"):
        group.attrs[key] = getattr(diagram, key)


def _write_periods(group: h5py.Group, regime) -> None:
    """The periodic regime, one row per whole period: a dataset per column on the dimension ``period``."""
    from .periodic.regime import PERIOD_DESCRIPTIONS

    table = regime.table
    group.attrs["period"] = regime.period
    group.attrs["period_units"] = "rad"
    group.attrs["settling_tolerance"] = regime.tolerance
    group.attrs["settled"] = regime.settled
    group.attrs["message"] = regime.message
    index = group.create_dataset("period", data=table["period"])
    index.attrs["units"] = "1"
    index.attrs["long_name"] = PERIOD_DESCRIPTIONS["period"]
    index.make_scale("period")
    for name, values in table.items():
        if name == "period":
            continue
        data = group.create_dataset(name, data=values)
        data.attrs["units"] = regime.units[name]
        data.attrs["long_name"] = PERIOD_DESCRIPTIONS.get(name, f"{name.removesuffix('_per_period')} "
                                                                "gained in the period (J)")
        data.dims[0].attach_scale(index)


# Summary columns the host adds to the elements' own (which declare their units).
_HOST_SUMMARY_UNITS = {"lock_events": "1", "unlock_events": "1", "energy_residual": "J",
                       "energy_relative_residual": "1"}


def _summary_units(scenario) -> dict[str, str]:
    """Units of every summary column: as the scene's elements declare them, yes/no values as 1."""
    from .assemble import machine_elements
    from .core.layout import Layout

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
            times = np.concatenate([time[on_grid], instants["time"][mine]])
            order = np.argsort(times, kind="stable")
            sorted_times = times[order]
            keep = np.append(sorted_times[1:] != sorted_times[:-1], True)  # an instant on a grid time: its row
            run = {name: np.concatenate([data[name][i][on_grid], after[name][mine]])[order][keep] for name in wanted}
            run["time"] = sorted_times[keep]
            table = np.zeros(int(mine.sum()), dtype=[("time", "f8"), ("kind", object), ("element", object),
                                                     ("torque_margin", "f8"), ("mode_after", object),
                                                     ("category", object)])
            for name in table.dtype.names:
                table[name] = instants[name][mine]
            run["events"] = table
            keys = summary if i == 0 or attributes is None else [k for k in attributes if k in summary]
            run["attrs"] = {**base, **{k: summary[k][i] for k in keys}}
            if f"periodic/{i}" in f:
                for name, part in f[f"periodic/{i}"].items():
                    run[name] = {k: v[()] for k, v in part.items()}
                    run[name]["attrs"] = dict(part.attrs)
            runs.append(run)
    return runs


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

"""HDF5 output, written atomically: a file is complete or absent.

Layout (the contract's names; see README):

    /runs/<i>/     one group per run; datasets share the dimension scale `time`,
                   so ``xarray.open_dataset(path, group="runs/0", engine="h5netcdf")``
                   reads it with time as the coordinate
    /runs/<i>/events   compound table (time, kind, element, torque_margin, mode_after)
    /runs/<i>/periods/ the periodic regime, one row per whole period (machines with a ripple or a slider-crank)
    /summary       one row per run
    /scenario      the scenario text, with provenance attributes
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
    """Write runs (in sweep order) to ``path`` atomically."""
    if not runs:
        raise ValueError("no runs to write")
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            f.attrs["format"] = "hoistsim-runs"
            f.attrs["format_version"] = 1
            for index, run in enumerate(runs):
                _write_run(f.create_group(f"runs/{index}"), run)
            _write_summary(f, [run.summary for run in runs], parameters or {}, _summary_units(runs[0].scenario))
            _write_scenario(f, runs[0].scenario, command)


def write_sweep(path, result, *, command: str = "") -> None:
    """Write a sweep: every run's time series, or (summary-only) the summary table alone."""
    if result.runs is not None:
        write_runs(path, result.runs, command=command, parameters=result.parameters)
        return
    with atomic_path(path) as tmp:
        with h5py.File(tmp, "w") as f:
            f.attrs["format"] = "hoistsim-runs"
            f.attrs["format_version"] = 1
            f.attrs["summary_only"] = True
            _write_summary(f, result.summaries, result.parameters, _summary_units(result.scenario))
            _write_scenario(f, result.scenario, command)


def _write_run(group: h5py.Group, run) -> None:
    scenario = run.scenario
    sim = scenario.simulation
    summary = run.summary
    group.attrs["name"] = run.name
    group.attrs["label"] = run.label or run.name
    group.attrs["parameters"] = json.dumps(scenario.resolved(), sort_keys=True)
    group.attrs["solver"] = sim.solver
    group.attrs["rtol"] = sim.rtol
    group.attrs["atol"] = sim.atol
    for key, value in summary.items():
        if key != "label":
            group.attrs[key] = value
    for key, value in run.energy_balance.items():
        group.attrs[f"energy_{key}"] = value
    for key, value in run.stats.items():
        group.attrs[f"solver_{key}"] = value

    time = group.create_dataset("time", data=run.time)
    time.attrs["units"] = "s"
    time.attrs["long_name"] = "time since the start"
    time.make_scale("time")
    for name, values in run.series.items():
        data = group.create_dataset(name, data=values)
        data.attrs["units"] = run.units[name]
        if name in run.descriptions:
            data.attrs["long_name"] = run.descriptions[name]
        data.dims[0].attach_scale(time)
    _write_events(group, run.events)
    if run.periodic is not None:
        _write_periods(group.create_group("periods"), run.periodic.regime)
        if run.periodic.diagram is not None:
            _write_diagram(group.create_group("turning_moment"), run.periodic.diagram)


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


def _write_events(group: h5py.Group, events: dict) -> None:
    count = len(events["time"])
    table = np.zeros(count, dtype=[("time", "f8"), ("kind", _TEXT), ("element", _TEXT), ("torque_margin", "f8"),
                                   ("mode_after", _TEXT)])
    for field in table.dtype.names:
        table[field] = events[field]
    data = group.create_dataset("events", data=table)
    data.attrs["units"] = "time: s, torque_margin: N*m"
    data.attrs["long_name"] = ("mode switches and scheduled events, and the element each belongs to; "
                               "torque_margin is that coupling's static capacity minus the torque it would "
                               "carry stuck (NaN for scheduled events)")
    index = group.create_dataset("event", data=np.arange(count))
    index.attrs["units"] = "1"
    index.make_scale("event")
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


def _write_summary(f: h5py.File, rows: list[dict], parameters: dict, units: dict[str, str]) -> None:
    """One row per run; swept keys become columns of their SI values (NaN for tables)."""
    fields = [("label", _TEXT)] + [(k, "f8") for k in parameters] + [
        (k, "f8" if isinstance(v, float) else "i8") for k, v in rows[0].items() if k != "label"]
    table = np.zeros(len(rows), dtype=fields)
    table["label"] = [row["label"] for row in rows]
    for key, values in parameters.items():
        table[key] = values
    for key, kind in fields[1 + len(parameters):]:
        table[key] = np.asarray([row[key] for row in rows], dtype=kind)
    data = f.create_dataset("summary", data=table)
    from .scenario import key_units

    units = {**{key: key_units(key) for key in parameters}, **units}  # the swept keys' SI units first
    data.attrs["units"] = ", ".join(f"{k}: {u}" for k, u in units.items())
    data.attrs["swept_keys"] = json.dumps(list(parameters))
    index = f.create_dataset("run", data=np.arange(len(rows)))
    index.attrs["units"] = "1"
    index.make_scale("run")
    data.dims[0].attach_scale(index)


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


def read_runs(path, columns=None, attributes=None) -> list[dict]:
    """Read the runs of a file back as dicts of numpy arrays (for plots and tables).

    ``columns``: the series to read (all when None); ``attributes``: the run
    attributes to read past the first run (all when None; the first run's are
    all read).  Events and the periodic regime's tables are always read.
    """
    runs = []
    with h5py.File(path, "r") as f:
        for index, key in enumerate(sorted(f.get("runs", {}), key=int)):
            group = f["runs"][key]
            names = set(group)
            wanted = names - {"events", "event"} if columns is None else names & set(columns)
            run = {}
            for name in wanted:
                item = group[name]
                if isinstance(item, h5py.Dataset):
                    run[name] = item[()]
            for name in names & {"periods", "turning_moment"}:  # the periodic regime's tables, with attributes
                run[name] = {k: v[()] for k, v in group[name].items()}
                run[name]["attrs"] = dict(group[name].attrs)
            run["events"] = group["events"][()]
            keep = None if index == 0 or attributes is None else attributes
            run["attrs"] = {k: group.attrs[k] for k in (group.attrs if keep is None else keep) if k in group.attrs}
            runs.append(run)
    return runs


def read_summary_units(path) -> dict[str, str]:
    """Each /summary column's units (the swept keys' are SI; "" where none is recorded)."""
    with h5py.File(path, "r") as f:
        text = f["summary"].attrs.get("units", "")
    text = text.decode() if isinstance(text, bytes) else str(text)
    return dict(item.split(": ", 1) for item in text.split(", ") if ": " in item)


def read_summary(path) -> list[dict]:
    """The /summary table of a results file as one dict per run (plain Python values)."""
    with h5py.File(path, "r") as f:
        table = f["summary"][()]
    rows = []
    for record in table:
        row = {}
        for name in table.dtype.names:
            value = record[name]
            if isinstance(value, bytes):
                value = value.decode()
            elif isinstance(value, np.generic):
                value = value.item()
            row[name] = value
        rows.append(row)
    return rows

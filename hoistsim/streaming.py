"""A sweep's results written as its chunks finish: memory bounded by a chunk, resumable after a kill.

Each finished chunk goes to a small file of its own in a folder beside the
target, ``.NAME.partial/``, written under a temporary name and renamed: a
killed process leaves whole chunks only (an HDF5 file killed while it is
being written can be left inconsistent, so the chunks are never written into
one).  The folder carries a key of what is being computed (the scenario's
text with its --set and --sweep, summary-only or not, the package's source).
When the last chunk is done, the results file (format 2, :mod:`hoistsim.output`)
is assembled from the chunks one at a time under a temporary name and takes
the target's name in one rename; the folder goes.  ``--resume`` checks the
key and runs only the chunks after those in the folder: chunks are computed
in a fixed order, so the file holds the same numbers as an uninterrupted run.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
from pathlib import Path

import h5py
import numpy as np

from . import output
from .output import _TEXT, _scale

_TEXT_COLUMNS = ("kind", "element", "category", "mode_after")
_INSTANT_COLUMNS = ("time", "kind", "element", "category", "torque_margin", "mode_after")
_INSTANT_TEXT = {"run": ("1", "the run it belongs to"), "time": ("s", "the instant, exact"),
                 "kind": ("1", "lock, unlock, reversal, engage, disengage, a scheduled event, an observation "
                               "(slip_peak, load_lowest, ...) or a period mark"),
                 "element": ("1", "the element it belongs to"),
                 "category": ("1", "switch, scheduled, observation or cycle"),
                 "torque_margin": ("N*m", "the coupling's static capacity minus the torque it would carry stuck "
                                          "(NaN where it does not apply)"),
                 "mode_after": ("1", "the coupling's mode after it")}


FILE_BYTES = 32 * 2**20  # series gathered into one chunk file
FILE_RUNS = 65536  # summaries gathered into one chunk file


class ResumeError(Exception):
    """--resume cannot go on (another scenario, other options, nothing to resume)."""


def partial_path(target) -> Path:
    target = Path(target)
    return target.with_name(f".{target.name}.partial")


def resume_key(scenario, summary_only: bool) -> str:
    """What the file is a computation of: a partial sweep is resumed only by the same computation."""
    from ._jax import source_digest

    text = json.dumps([scenario.text, bool(summary_only), source_digest()])
    return hashlib.sha256(text.encode()).hexdigest()


class StreamedFile:
    """The results of a sweep, kept chunk by chunk and assembled at the end (see the module docstring)."""

    def __init__(self, target, scenario, labels, parameters: dict, *, summary_only: bool, command: str = "",
                 resume: bool = False):
        self.target, self.folder = Path(target), partial_path(target)
        self.scenario, self.labels, self.parameters = scenario, labels, parameters
        self.summary_only, self.command = summary_only, command
        self.key = resume_key(scenario, summary_only)
        self.time, self.padded = None, False
        self.discarded = 0
        if resume:
            if not (self.folder / "key").is_file():
                raise ResumeError(f"no interrupted sweep ({self.folder.name}) beside {self.target.name} to resume; "
                                  "run without --resume")
            if (self.folder / "key").read_text() != self.key:
                raise ResumeError(f"{self.folder.name} holds another scenario or other options (or another "
                                  "hoistsim); run without --resume to start again")
        else:  # a fresh start: an interrupted sweep's chunks there go (said: ``discarded``)
            self.discarded = len(list(self.folder.glob("chunk-*.h5"))) if self.folder.is_dir() else 0
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder.mkdir()
            (self.folder / "key").write_text(self.key)
        # whole files only (each appears by a rename); a file holds one or more of the sweep's chunks
        self.files, self.chunks_done = 0, 0
        while self._chunk(self.files + 1).is_file():
            self.files += 1
            with h5py.File(self._chunk(self.files), "r") as f:
                self.chunks_done += int(f.attrs["sweep_chunks"])
        self.resumed_files = self.files
        self.pending: list = []  # chunks finished, not yet in a file: (indices, outcomes)

    def _chunk(self, number: int) -> Path:
        return self.folder / f"chunk-{number:07d}.h5"

    # ------------------------------------------------------------------ the chunks

    def begin(self, grids) -> None:
        """The output grids of every run: the common time axis (full output only)."""
        if self.summary_only:
            return
        grids = [np.asarray(g) for g in grids]
        same = all(g.shape == grids[0].shape and np.array_equal(g, grids[0]) for g in grids[1:])
        self.time = grids[0] if same else np.unique(np.concatenate(grids))
        self.padded = not same  # some run lacks some rows: every series is float, NaN there

    def write(self, indices, outcomes) -> None:
        """One finished chunk: its runs (RunResults, or summary dicts when summary-only), at ``indices``.

        Chunks are gathered into files of about FILE_BYTES of series (or FILE_RUNS summaries): few
        files, each written once; what a kill loses is at most one file's worth of runs.
        """
        self.pending.append((list(indices), list(outcomes)))
        runs = sum(len(i) for i, _ in self.pending)
        size = 0 if self.summary_only else runs * self.time.size * 8 * len(outcomes[0].series)
        if size >= FILE_BYTES or runs >= FILE_RUNS:
            self._flush()

    def _flush(self) -> None:
        if not self.pending:
            return
        indices = [i for part, _ in self.pending for i in part]
        outcomes = [o for _, part in self.pending for o in part]
        self.files += 1
        final = self._chunk(self.files)
        partial = final.with_suffix(".tmp")
        with h5py.File(partial, "w") as f:
            f.attrs["sweep_chunks"] = len(self.pending)
            f["indices"] = np.asarray(indices, dtype=np.int64)
            summaries = [o if self.summary_only else o.summary for o in outcomes]
            f.attrs["columns"] = json.dumps([k for k in summaries[0] if k != "label"])
            values = f.create_group("values")
            for key in json.loads(f.attrs["columns"]):  # as the file at once has them: floats, else integers
                values[key] = np.asarray([row[key] for row in summaries],
                                         dtype="f8" if isinstance(summaries[0][key], float) else "i8")
            if not self.summary_only:
                self._write_runs(f, outcomes)
        os.replace(partial, final)
        self.pending = []

    def _write_runs(self, f: h5py.File, runs) -> None:
        for key, (units, values) in output._run_extras(runs).items():
            f[f"extras/{key}"] = values
            f[f"extras/{key}"].attrs["units"] = units
        series = f.create_group("series")
        first = runs[0]
        for name, values in first.series.items():
            dtype = np.float64 if self.padded or values.dtype.kind == "f" else values.dtype
            block = np.full((len(runs), self.time.size), np.nan if dtype == np.float64 else 0, dtype=dtype)
            for k, run in enumerate(runs):
                place = np.searchsorted(self.time, run.grid) if run.grid is not None else slice(None)
                block[k, place] = run.series[name][run.grid_rows()]
            series[name] = block
            series[name].attrs["units"] = first.units[name]
            series[name].attrs["long_name"] = first.descriptions.get(name, "")
        tables = [run.all_instants() for run in runs]
        counts = [len(t["time"]) for t in tables]
        instants = f.create_group("instants")
        instants["counts"] = np.asarray(counts, dtype=np.int64)
        for name in _INSTANT_COLUMNS:
            values = np.concatenate([np.asarray(t[name]) for t in tables])
            instants.create_dataset(name, data=values.astype(object) if name in _TEXT_COLUMNS else values.astype(float),
                                    **({"dtype": _TEXT} if name in _TEXT_COLUMNS else {}))
        after = f.create_group("after")
        for name in first.series:
            after[name] = np.concatenate([run.series[name][run.instant_rows()] for run in runs])
        for k, run in enumerate(runs):
            if run.periodic is not None:
                group = f.create_group(f"periodic/{k}")
                output._write_periods(group.create_group("periods"), run.periodic.regime)
                if run.periodic.diagram is not None:
                    output._write_diagram(group.create_group("turning_moment"), run.periodic.diagram)

    def written_summaries(self) -> dict[int, dict]:
        """The summaries of the runs in chunks written before a resume, by run index."""
        rows = {}
        for number in range(1, self.resumed_files + 1):
            with h5py.File(self._chunk(number), "r") as f:
                columns = json.loads(f.attrs["columns"])
                values = {key: f[f"values/{key}"][()].tolist() for key in columns}
                for k, i in enumerate(f["indices"][()]):
                    rows[int(i)] = {"label": self.labels[int(i)], **{key: values[key][k] for key in columns}}
        return rows

    # ------------------------------------------------------------------ the file

    def finish(self) -> None:
        """Assemble the results file from the chunks, one at a time; it takes the target's name atomically."""
        self._flush()
        with output.atomic_path(self.target) as tmp:
            with h5py.File(tmp, "w") as f:
                _Assembly(f, self).build([self._chunk(n) for n in range(1, self.files + 1)])
        shutil.rmtree(self.folder, ignore_errors=True)

    def discard(self) -> None:
        """Forget the sweep (a run failed): no chunk is left behind."""
        shutil.rmtree(self.folder, ignore_errors=True)

    def close(self) -> None:
        """Stop, leaving the chunks for --resume (after an interruption)."""
        for leftover in self.folder.glob("*.tmp"):
            with contextlib.suppress(OSError):
                leftover.unlink()


class _Assembly:
    """Format 2 from chunk files: the (run) and (run, time) variables filled chunk by chunk, instants appended."""

    def __init__(self, f: h5py.File, stream: StreamedFile):
        self.f, self.stream = f, stream
        self.count = len(stream.labels)
        self.instants = 0

    def build(self, chunks) -> None:
        f, stream = self.f, self.stream
        output._start_file(f, stream.summary_only)
        group = f.create_group("runs")
        run = _scale(group, "run", np.arange(self.count), "1", "run index, in sweep order")
        output._variable(group, "label", np.asarray(stream.labels, dtype=object), "1",
                         "the run's swept values (or the scenario's name)", (run,), dtype=_TEXT)
        from .scenario import key_units

        for key, values in stream.parameters.items():
            output._variable(group, key, np.asarray(values, dtype=float), key_units(key), f"swept: {key} (SI)", (run,))
        if stream.time is not None:
            _scale(group, "time", stream.time, "s", "time since the start (the output grid; exact instants are in events)")
        units = output._summary_units(stream.scenario)
        columns = None
        for path in chunks:
            with h5py.File(path, "r") as chunk:
                columns = columns or json.loads(chunk.attrs["columns"])
                self._chunk(group, chunk, units)
        group.attrs["summary_columns"] = json.dumps(["label", *stream.parameters, *(columns or [])])
        group.attrs["swept_keys"] = json.dumps(list(stream.parameters))
        group.attrs["name"] = stream.scenario.name
        group.attrs["parameters"] = json.dumps(stream.scenario.resolved(), sort_keys=True)
        sim = stream.scenario.simulation
        group.attrs["solver"], group.attrs["rtol"], group.attrs["atol"] = sim.solver, sim.rtol, sim.atol
        output._write_scenario(f, stream.scenario, stream.command)

    def _column(self, group, name, dtype, units, text="", time_axis=False, rows=1):
        if name in group:
            return group[name]
        shape = (self.count, group["time"].shape[0]) if time_axis else (self.count,)
        options = {}
        if time_axis:  # an HDF5 chunk a sweep chunk: each is written once, never read back and rewritten
            options = dict(chunks=(min(self.count, rows), shape[1]), compression="gzip", compression_opts=1,
                           shuffle=True)
        data = group.create_dataset(name, shape=shape, dtype=dtype,
                                    fillvalue=np.nan if np.dtype(dtype).kind == "f" else 0, **options)
        data.attrs["units"] = units
        if text:
            data.attrs["long_name"] = text
        data.dims[0].attach_scale(group["run"])
        if time_axis:
            data.dims[1].attach_scale(group["time"])
        return data

    def _chunk(self, group, chunk, units) -> None:
        indices = chunk["indices"][()]
        rows = slice(int(indices[0]), int(indices[-1]) + 1) if indices[-1] - indices[0] + 1 == len(indices) else indices
        for key, item in chunk["values"].items():
            self._column(group, key, item.dtype, units.get(key, ""))[rows] = item[()]
        for key, item in chunk.get("extras", {}).items():
            if key not in chunk["values"]:
                self._column(group, key, item.dtype, str(item.attrs["units"]))[rows] = item[()]
        for name, item in chunk.get("series", {}).items():
            self._column(group, name, item.dtype, str(item.attrs["units"]), str(item.attrs["long_name"]),
                         time_axis=True, rows=len(indices))[rows] = item[()]
        if "instants" in chunk:
            self._instants(group, chunk, indices)
        for key, part in chunk.get("periodic", {}).items():
            self.f.copy(part, self.f.require_group("periodic"), name=str(int(indices[int(key)])))

    def _instants(self, group, chunk, indices) -> None:
        events = group.require_group("events")
        counts = chunk["instants/counts"][()]
        columns = {"run": np.repeat(indices, counts).astype(np.int64)}
        for name in _INSTANT_COLUMNS:
            item = chunk[f"instants/{name}"]
            columns[name] = item.asstr()[()].astype(object) if name in _TEXT_COLUMNS else item[()]
        after = {name: item for name, item in chunk["after"].items()}
        if "event" not in events:
            scale = events.create_dataset("event", shape=(0,), maxshape=(None,), dtype=np.int64, chunks=(4096,))
            scale.attrs["units"] = "1"
            scale.attrs["long_name"] = "instant index, runs in order"
            scale.make_scale("event")
            for name, values in [*columns.items(), *((n, a) for n, a in after.items())]:
                units, text = _INSTANT_TEXT.get(name, (group[name].attrs["units"] if name in group else "",
                                                       "value just after the instant"))
                dtype = _TEXT if name in _TEXT_COLUMNS else values.dtype
                data = events.create_dataset(name, shape=(0,), maxshape=(None,), dtype=dtype, chunks=(4096,))
                data.attrs["units"] = units
                data.attrs["long_name"] = text
                data.dims[0].attach_scale(scale)
        added = int(counts.sum())
        start = self.instants
        for name, values in {"event": np.arange(start, start + added), **columns,
                             **{n: a[()] for n, a in after.items()}}.items():
            data = events[name]
            data.resize((start + added,))
            data[start:] = values
        self.instants += added

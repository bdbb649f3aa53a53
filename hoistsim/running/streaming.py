"""A sweep's results written as its chunks finish: memory bounded by a chunk, resumable after a kill.

Each finished chunk goes to a small file of its own in a folder beside the
target, ``.NAME.partial/``, written under a temporary name and renamed: a
killed process leaves whole chunks only (an HDF5 file killed while it is
being written can be left inconsistent, so the chunks are never written into
one).  The folder carries a key of what is being computed (the scenario's
text with its --set and --sweep, summary-only or not, the package's source).
When the last chunk is done, the results file (format 2, :mod:`hoistsim.results.output`)
is assembled from the chunks one at a time under a temporary name and takes
the target's name in one rename; the folder goes.  ``--resume`` checks the
key and runs only the chunks after those in the folder: chunks are computed
in a fixed order, so the file holds the same numbers as an uninterrupted run.
Chunk files are written by size and by time (every FILE_SECONDS at the
latest), so a kill loses seconds of work; ``--resume`` where nothing was kept
starts afresh and says so.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import shutil
import time
from pathlib import Path

import h5py
import numpy as np

from ..results import output
from ..results.records import Record, joined, make_record, read_record
from ..results.summaries import Summaries

FILE_BYTES = 32 * 2**20  # series gathered into one chunk file
FILE_RUNS = 65536  # summaries gathered into one chunk file
FILE_SECONDS = 10.0  # and at the latest: a kill loses at most the runs of the last ten seconds or so
clock = time.monotonic


class ResumeError(Exception):
    """--resume cannot go on (another scenario, other options, nothing to resume)."""


def partial_path(target) -> Path:
    target = Path(target)
    return target.with_name(f".{target.name}.partial")


def resume_key(scenario, summary_only: bool, split: tuple = ()) -> str:
    """What the file is a computation of: a partial sweep is resumed only by the same computation.

    ``split``: how the runs are cut (the chunk width, and the devices a chunk is split over): blocks are
    counted in chunks, and the numbers are the same bits only for the same split.
    """
    from ..program_origin import source_digest

    text = json.dumps([scenario.text, bool(summary_only), source_digest(), list(split)])
    return hashlib.sha256(text.encode()).hexdigest()


class StreamedFile:
    """The results of a sweep, kept chunk by chunk and assembled at the end (see the module docstring)."""

    def __init__(self, target, scenario, labels, parameters: dict, *, summary_only: bool, command: str = "",
                 resume: bool = False, split: tuple = ()):
        self.target, self.folder = Path(target), partial_path(target)
        self.scenario, self.labels, self.parameters = scenario, labels, parameters
        self.summary_only, self.command = summary_only, command
        self.key = resume_key(scenario, summary_only, split)
        self.time, self.padded = None, False
        self.discarded = 0
        self.nothing_to_resume = resume and not (self.folder / "key").is_file()  # then a fresh start, said
        if resume and not self.nothing_to_resume:
            if (self.folder / "key").read_text() != self.key:
                raise ResumeError(f"{self.folder.name} holds another scenario or other options (or another "
                                  "hoistsim, chunk size or CPU device count); run without --resume to start again")
        else:  # a fresh start: an interrupted sweep's chunks there go (said: ``discarded``)
            self.discarded = len(list(self.folder.glob("chunk-*.h5"))) if self.folder.is_dir() else 0
            shutil.rmtree(self.folder, ignore_errors=True)
            self.folder.mkdir()
            (self.folder / "key").write_text(self.key)
        # whole files only (each appears by a rename); a file holds one or more of the sweep's blocks
        self.files, self.blocks_done = 0, 0
        while self._chunk(self.files + 1).is_file():
            self.files += 1
            with h5py.File(self._chunk(self.files), "r") as f:
                self.blocks_done += int(f.attrs["sweep_blocks"])
        self.pending: list = []  # blocks finished, not yet in a file
        self.written_at = clock()  # when the last file was written (or the sweep began)

    def _chunk(self, number: int) -> Path:
        return self.folder / f"chunk-{number:07d}.h5"

    # ------------------------------------------------------------------ the chunks

    def begin(self, grids) -> None:
        """The output grids of every run: the common time axis (full output only)."""
        if not self.summary_only:
            self.time, self.padded = output.common_time(grids)

    def write(self, block) -> None:
        """One finished block of runs (:class:`hoistsim.running.blocks.Block`).

        Blocks are gathered into files of about FILE_BYTES of series (or FILE_RUNS summaries): few
        files, each written once; and a file is written at the latest FILE_SECONDS after the last, so
        that a kill loses at most the blocks of those seconds (and the one under way).
        """
        self.pending.append(block)
        runs = sum(b.stop - b.start for b in self.pending)
        size = 0 if self.summary_only else runs * self.time.size * 8 * len(
            block.outcome.series if isinstance(block.outcome, Record) else block.outcome[0].series)
        if size >= FILE_BYTES or runs >= FILE_RUNS or clock() - self.written_at >= FILE_SECONDS:
            self._flush()

    def _flush(self) -> None:
        if not self.pending:
            return
        indices = np.arange(self.pending[0].start, self.pending[-1].stop)
        made = [b.outcome for b in self.pending if isinstance(b.outcome, Record)]  # read from the chunks' arrays
        if self.summary_only:
            outcomes = Summaries.concatenate([b.outcome for b in self.pending])
        else:
            outcomes = [run for b in self.pending if not isinstance(b.outcome, Record) for run in b.outcome]
            if made and outcomes:  # runs made one by one beside them: a record of their own, joined to them
                made.append(make_record(np.concatenate([np.arange(b.start, b.stop) for b in self.pending
                                                        if not isinstance(b.outcome, Record)]),
                                        outcomes, summary_only=False, time=self.time, padded=self.padded))
            outcomes = joined(made) if made else outcomes
        self.files += 1
        final = self._chunk(self.files)
        partial = final.with_suffix(".tmp")
        with h5py.File(partial, "w") as f:
            f.attrs["sweep_blocks"] = len(self.pending)
            output.write_record(f, indices, outcomes, summary_only=self.summary_only, time=self.time,
                                padded=self.padded)
        os.replace(partial, final)
        self.pending = []
        self.written_at = clock()

    # ------------------------------------------------------------------ the file

    def finish(self) -> None:
        """Assemble the results file from the chunk files, one at a time; it takes the target's name atomically."""
        self._flush()
        from .simulation import scene_summary_units

        heading = output.Heading(self.scenario, self.labels, self.parameters, self.summary_only, self.time,
                                 scene_summary_units(self.scenario), self.command)
        output.assemble(self.target, self._records(), heading)
        shutil.rmtree(self.folder, ignore_errors=True)

    def _records(self):
        for number in range(1, self.files + 1):
            with h5py.File(self._chunk(number), "r") as f:
                yield read_record(f)

    def discard(self) -> None:
        """Forget the sweep (a run failed): no chunk is left behind."""
        shutil.rmtree(self.folder, ignore_errors=True)

    def close(self) -> None:
        """Stop, leaving the chunks for --resume (after an interruption)."""
        for leftover in self.folder.glob("*.tmp"):
            with contextlib.suppress(OSError):
                leftover.unlink()

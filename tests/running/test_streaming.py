"""A sweep's file is written as its chunks finish, and an interrupted sweep resumes to the same numbers."""

from __future__ import annotations

import signal
import subprocess
import sys
import textwrap

import numpy as np
import pytest
from click.testing import CliRunner
from helpers import SWEEP_FILE, datasets, same, short_sweep

from hoistsim import sweep
from hoistsim.cli import main
from hoistsim.running.streaming import ResumeError, StreamedFile, partial_path


class _Stop(Exception):
    pass


@pytest.fixture(autouse=True)
def a_file_a_chunk(monkeypatch):
    """Every chunk a block, every block in a file of its own (a sweep of a few short runs would otherwise
    fill one block and one file)."""
    from hoistsim.running import streaming, sweeps

    monkeypatch.setattr(streaming, "FILE_RUNS", 1)
    monkeypatch.setattr(sweeps, "BLOCK_CHUNKS", 1)


def _interrupted(scenario, target, chunks: int, summary_only: bool, monkeypatch):
    """Run the sweep to ``target`` and stop it after ``chunks`` chunks are written."""
    written = {"n": 0}
    original = StreamedFile.write

    def write(self, block):
        original(self, block)
        written["n"] += 1
        if written["n"] == chunks:
            raise _Stop

    monkeypatch.setattr(StreamedFile, "write", write)
    with pytest.raises(_Stop):
        sweep(scenario, summary_only=summary_only, chunk_size=4, output=target)
    monkeypatch.setattr(StreamedFile, "write", original)


@pytest.mark.parametrize("summary_only", [pytest.param(False, marks=pytest.mark.slow), True])
def test_a_resumed_sweep_equals_an_uninterrupted_one(tmp_path, monkeypatch, summary_only):
    scenario = short_sweep(10)
    whole = sweep(scenario, summary_only=summary_only, chunk_size=4, output=tmp_path / "whole.h5")
    _interrupted(scenario, tmp_path / "resumed.h5", 2, summary_only, monkeypatch)
    assert not (tmp_path / "resumed.h5").exists() and partial_path(tmp_path / "resumed.h5").exists()
    assert len(list(partial_path(tmp_path / "resumed.h5").glob("chunk-*.h5"))) == 2  # two whole chunks kept
    resumed = sweep(scenario, summary_only=summary_only, chunk_size=4, output=tmp_path / "resumed.h5", resume=True)
    assert not partial_path(tmp_path / "resumed.h5").exists()
    same(datasets(tmp_path / "whole.h5"), datasets(tmp_path / "resumed.h5"))
    assert [r["lockup_time"] for r in resumed.summaries] == pytest.approx(
        [r["lockup_time"] for r in whole.summaries], nan_ok=True, rel=0, abs=0)


@pytest.mark.slow
def test_the_streamed_file_is_the_file_written_at_once(tmp_path):
    scenario = short_sweep(6)
    sweep(scenario, chunk_size=4, output=tmp_path / "streamed.h5")
    sweep(scenario, chunk_size=4).to_hdf5(tmp_path / "at_once.h5")  # the same chunks: the same bits
    same(datasets(tmp_path / "streamed.h5"), datasets(tmp_path / "at_once.h5"))


@pytest.mark.slow
def test_a_record_read_from_the_chunks_arrays_is_the_record_of_the_runs(tmp_path):
    """A streamed sweep's record is read straight from each chunk's arrays; the runs of a chunk go in the
    order of their swept values (here the reverse of the sweep's), and come back in the sweep's order: the
    file is the one written from each run's RunResult, bit for bit."""
    from hoistsim import load_scenario

    scenario = load_scenario(SWEEP_FILE, overrides=["simulation.duration=0.4 s"],
                             sweeps=["clutch.engagement_force=12 kN,9 kN,7 kN,5 kN,3 kN"])
    sweep(scenario, chunk_size=4, output=tmp_path / "streamed.h5")
    sweep(scenario, chunk_size=4).to_hdf5(tmp_path / "at_once.h5")
    same(datasets(tmp_path / "streamed.h5"), datasets(tmp_path / "at_once.h5"))


def test_resume_refuses_another_scenario_in_one_line(tmp_path, monkeypatch):
    target = tmp_path / "forces.h5"
    _interrupted(short_sweep(10), target, 1, True, monkeypatch)
    with pytest.raises(ResumeError, match="holds another scenario or other options"):
        sweep(short_sweep(12), summary_only=True, chunk_size=4, output=target, resume=True)
    result = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(target), "--summary-only", "--resume",
                                       "--set", "simulation.duration=0.4 s",
                                       "--sweep", "clutch.engagement_force=3 kN:12 kN:11"])
    assert result.exit_code == 2
    lines = result.output.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error: --resume: ") and not target.exists()


def test_resume_with_nothing_kept_starts_afresh_and_says_so_in_one_line(tmp_path):
    target = tmp_path / "new.h5"
    nothing = CliRunner().invoke(main, ["run", str(SWEEP_FILE), "-o", str(target), "--summary-only", "--resume",
                                        "--set", "simulation.duration=0.4 s",
                                        "--sweep", "clutch.engagement_force=3 kN:12 kN:4"])
    assert nothing.exit_code == 0, nothing.output
    notices = [line for line in nothing.output.splitlines() if line.startswith("hoistsim: warning:")]
    assert notices == ["hoistsim: warning: new.h5: nothing was kept to resume (no .new.h5.partial); started afresh"]
    assert target.exists() and not partial_path(target).exists()


def test_a_sweep_keeps_its_finished_blocks_every_few_seconds_and_a_resume_redoes_only_those_after(
        tmp_path, monkeypatch):
    """Files by time as well as by size: blocks that each take 4 s (a clock that says so) under a 10 s
    limit go to a file every third block; stopped after five blocks (as a kill would stop it), the
    sweep keeps three, loses the two of the last 8 s, and --resume ends with the file of a whole run."""
    from hoistsim.running import streaming

    monkeypatch.setattr(streaming, "FILE_RUNS", 10**6)  # never by count here
    now = [0.0]
    monkeypatch.setattr(streaming, "clock", lambda: now[0])
    original = StreamedFile.write

    def four_seconds_a_block(self, block):
        now[0] += 4.0
        original(self, block)

    monkeypatch.setattr(StreamedFile, "write", four_seconds_a_block)
    scenario, target = short_sweep(24), tmp_path / "timed.h5"
    _interrupted(scenario, target, 5, True, monkeypatch)
    kept = sorted(partial_path(target).glob("chunk-*.h5"))
    assert len(kept) == 1
    import h5py

    with h5py.File(kept[0]) as f:
        assert int(f.attrs["sweep_blocks"]) == 3
    monkeypatch.setattr(StreamedFile, "write", four_seconds_a_block)
    redone = {"blocks": 0}
    counting = StreamedFile.write

    def counted(self, block):
        redone["blocks"] += 1
        counting(self, block)

    monkeypatch.setattr(StreamedFile, "write", counted)
    sweep(scenario, summary_only=True, chunk_size=4, output=target, resume=True)
    assert redone["blocks"] == 6 - 3  # 24 runs in blocks of 4: only those after the kept three
    sweep(scenario, summary_only=True, chunk_size=4, output=tmp_path / "whole.h5")
    same(datasets(tmp_path / "whole.h5"), datasets(target))


@pytest.mark.slow
def test_a_sweep_killed_while_writing_a_chunk_resumes_from_the_last_whole_one(tmp_path):
    """SIGKILL while the second chunk is being written: it is not among the chunks kept, --resume redoes it."""
    target = tmp_path / "killed.h5"
    script = textwrap.dedent(f"""
        import os, signal
        from hoistsim import load_scenario, sweep
        from hoistsim.running import streaming, sweeps
        streaming.FILE_RUNS = 1
        sweeps.BLOCK_CHUNKS = 1
        calls = {{"n": 0}}
        original = streaming.output.write_record
        def write_record(*args, **kwargs):
            calls["n"] += 1
            original(*args, **kwargs)
            if calls["n"] == 2:  # the chunk's data written, its file not yet renamed into place
                os.kill(os.getpid(), signal.SIGKILL)
        streaming.output.write_record = write_record
        s = load_scenario({str(SWEEP_FILE)!r}, overrides=["simulation.duration=0.4 s"],
                          sweeps=["clutch.engagement_force=3 kN:12 kN:10"])
        sweep(s, chunk_size=4, output={str(target)!r})
    """)
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True)
    assert proc.returncode == -signal.SIGKILL and not target.exists()
    sweep(short_sweep(10), chunk_size=4, output=target, resume=True)
    sweep(short_sweep(10), chunk_size=4, output=tmp_path / "whole.h5")
    same(datasets(tmp_path / "whole.h5"), datasets(target))


def test_starting_afresh_over_an_interrupted_sweep_says_so(tmp_path, monkeypatch):
    target = tmp_path / "forces.h5"
    _interrupted(short_sweep(10), target, 1, True, monkeypatch)
    again = sweep(short_sweep(10), summary_only=True, chunk_size=4, output=target)
    assert again.warnings == ["forces.h5: an interrupted sweep's 1 chunk file(s) were discarded (--resume keeps them)"]
    assert target.exists() and not partial_path(target).exists()


def test_a_streamed_sweep_reads_its_summaries_back_as_they_were(tmp_path):
    """A streamed sweep keeps nothing per run in memory: its summaries are read back from the file when
    asked for, the same values and types as a sweep kept in memory (yes/no values as bools)."""
    from hoistsim.results.reading import FileSummaries

    scenario = short_sweep(10)
    kept = sweep(scenario, summary_only=True, chunk_size=4)
    streamed = sweep(scenario, summary_only=True, chunk_size=4, output=tmp_path / "s.h5")
    assert isinstance(streamed.summaries, FileSummaries) and len(streamed.summaries) == len(kept.summaries) == 10
    for a, b in zip(kept.summaries, streamed.summaries):
        assert list(a) == list(b)
        for key in a:
            assert type(a[key]) is type(b[key]), key
            assert a[key] == b[key] or (a[key] != a[key] and b[key] != b[key]), key  # NaN where NaN
    assert streamed.summaries[-1] == kept.summaries[-1] or np.isnan(kept.summaries[-1]["lockup_time"])
    assert [row["label"] for row in streamed.summaries[2:5]] == list(kept.labels[2:5])
    np.testing.assert_array_equal(streamed.summary["slip_energy"], kept.summary["slip_energy"])

"""`hoistsim watch`: each save runs the scenario again; a new value never compiles, a bad edit keeps the last results."""

from __future__ import annotations

import contextlib
import os
import subprocess
import sys
import threading
import time
from pathlib import Path

import h5py
import numpy as np
import pytest
from helpers import SCENARIOS, SHORT, with_force

from hoistsim import _jax
from hoistsim.cli.watching import Watch, watch
from hoistsim.program_pool import ProgramPool


@contextlib.contextmanager
def _noted(name):
    compiled.append(name)
    yield


compiled: list[str] = []


def test_a_new_value_reruns_without_compiling_and_a_bad_edit_keeps_the_last_results(tmp_path, monkeypatch):
    assert "duration: 0.4 s" in SHORT
    monkeypatch.setattr(_jax, "programs", ProgramPool())  # none held from other tests
    monkeypatch.setattr(_jax, "compile_notice", _noted)
    compiled.clear()
    scenario, output = tmp_path / "scene.yaml", tmp_path / "scene.h5"
    said = []
    watched = Watch(scenario, output=output, echo=said.append)
    scenario.write_text(with_force(SHORT, 3200), encoding="utf-8")
    assert watched.run()
    assert len(compiled) == 1
    with h5py.File(output) as f:
        first = f["runs/engagement_force"][0, -1] if "engagement_force" in f["runs"] else None
        first_heat = float(f["runs/slip_energy"][0])
    scenario.write_text(with_force(SHORT, 2600), encoding="utf-8")  # a new value: slips, never locks
    assert watched.run()
    assert len(compiled) == 1  # the compiled loop served
    with h5py.File(output) as f:
        assert float(f["runs/slip_energy"][0]) != first_heat
        if first is not None:
            assert f["runs/engagement_force"][0, -1] == 2600
    kept = output.read_bytes()
    scenario.write_text(with_force(SHORT, 2600).replace("engagement_force: 2600 N", "engagement_force: [["),
                        encoding="utf-8")
    assert not watched.run()
    assert said[-1].startswith("hoistsim: error: ") and "engagement_force" in said[-1]
    assert said[-1].endswith("(the last good results are kept)") and len(said[-1].splitlines()) == 1
    assert output.read_bytes() == kept
    assert "clutch never locks" in said[1] and said[1].startswith(tuple("0123456789"))
    scenario.write_text(with_force(SHORT, 2600).replace("solver: tsit5", "solver: dopri5"), encoding="utf-8")
    assert watched.run()  # another solver: another structure, compiled once
    assert len(compiled) == 2
    watched.close()


def _pixels(path):
    from PIL import Image

    return np.asarray(Image.open(path), dtype=int)


def test_the_figure_drawn_beside_the_file_is_the_one_the_file_draws(tmp_path):
    """The figure is drawn from the run while the results file is written: pixel for pixel what
    `hoistsim plot` draws from that file, at each save; with no -o, no results file is written at all."""
    from hoistsim.figures.files import plot_file

    scenario, output, figure = tmp_path / "scene.yaml", tmp_path / "scene.h5", tmp_path / "scene.png"
    watched = Watch(scenario, output=output, figure=figure, echo=lambda line: None)
    for force in (3200, 2600):  # locks; slips and runs back
        scenario.write_text(with_force(SHORT, force), encoding="utf-8")
        assert watched.run()
        plot_file(output, tmp_path / "plotted.png")
        assert np.array_equal(_pixels(figure), _pixels(tmp_path / "plotted.png")), force
    watched.close()
    alone = Watch(scenario, figure=tmp_path / "alone.png", echo=lambda line: None)
    assert alone.run()
    assert np.array_equal(_pixels(tmp_path / "alone.png"), _pixels(figure))
    assert alone._scratch is None and sorted(p.name for p in tmp_path.iterdir()) == [
        "alone.png", "plotted.png", "scene.h5", "scene.png", "scene.yaml"]
    alone.close()


@pytest.mark.slow
def test_a_periodic_regime_is_drawn_from_its_file(tmp_path):
    """The periodic regime's figures are made from its file: watch writes one aside and draws both."""
    scenario, figure = tmp_path / "ripple.yaml", tmp_path / "ripple.png"
    scenario.write_text((SCENARIOS / "motor_ripple_tredgold.yaml").read_text(encoding="utf-8"),
                        encoding="utf-8")
    watched = Watch(scenario, figure=figure, echo=lambda line: None)
    assert watched.run()
    assert figure.exists() and (tmp_path / "ripple_periodic.png").exists()
    assert (Path(watched._scratch.name) / "results.h5").exists()
    watched.close()


def test_a_save_made_while_the_first_run_runs_is_run_too(tmp_path):
    """The first run compiles for seconds before the files are watched: a save meanwhile is not lost."""
    scenario = tmp_path / "scene.yaml"
    scenario.write_text(with_force(SHORT, 3200), encoding="utf-8")
    said, stop = [], threading.Event()

    class SavedDuringTheFirstRun(Watch):
        def run(self):
            ran = super().run()
            if self.runs == 1:
                scenario.write_text(with_force(SHORT, 2600), encoding="utf-8")  # the run had read the file already
            else:
                stop.set()
            return ran

    watched = SavedDuringTheFirstRun(scenario, echo=said.append)
    loop = threading.Thread(target=watch, args=(watched, stop), daemon=True)
    loop.start()
    loop.join(60)
    stop.set()
    assert not loop.is_alive() and watched.runs == 2, said
    assert "clutch never locks" in said[-1]


def test_a_sweep_is_refused_with_its_key(tmp_path):
    scenario = tmp_path / "scene.yaml"
    scenario.write_text(SHORT + "sweep:\n  clutch.engagement_force: [2600 N, 3000 N]\n", encoding="utf-8")
    said = []
    assert not Watch(scenario, echo=said.append).run()
    assert said == [f"hoistsim: error: {scenario}: sweep: watch runs one scenario: remove the sweep: section "
                    "(hoistsim run sweeps it)"]


@pytest.mark.slow
def test_the_command_runs_again_at_each_save_and_redraws_the_figure(tmp_path):
    """The real loop: a process watching the file through the operating system's notifications."""
    scenario, figure = tmp_path / "scene.yaml", tmp_path / "scene.png"
    scenario.write_text(with_force(SHORT, 3200), encoding="utf-8")
    env = dict(os.environ, HOISTSIM_CACHE_DIR=str(tmp_path / "cache"), PYTHONUNBUFFERED="1")
    proc = subprocess.Popen([sys.executable, "-m", "hoistsim.cli", "watch", str(scenario), "--plot", str(figure)],
                            cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    out, err = [], []
    for stream, lines in ((proc.stdout, out), (proc.stderr, err)):
        threading.Thread(target=lambda s=stream, l=lines: [l.append(line) for line in s], daemon=True).start()

    def wait_for(lines, count, seconds=120):
        deadline = time.monotonic() + seconds
        while len(lines) < count and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.02)
        assert len(lines) >= count, (out, err)

    try:
        wait_for(out, 1)
        while not figure.exists():
            time.sleep(0.02)
        drawn = figure.stat().st_ino
        time.sleep(0.2)
        scenario.write_text(with_force(SHORT, 2600), encoding="utf-8")
        wait_for(out, 2, 30)
        assert "clutch never locks" in out[1]
        deadline = time.monotonic() + 30
        while figure.stat().st_ino == drawn and time.monotonic() < deadline:
            time.sleep(0.02)
        assert figure.stat().st_ino != drawn  # replaced whole, by rename
        compiling = [line for line in err if "compiling" in line]
        assert len(compiling) == 1  # the first run's; the new value loaded nothing, compiled nothing
        scenario.write_text("clutch: [\n", encoding="utf-8")
        wait_for(err, len(err) + 1, 30)
        assert err[-1].startswith("hoistsim: error: ") and proc.poll() is None
    finally:
        proc.terminate()
        proc.wait(20)


def test_the_headline_tells_each_clutchs_story_as_the_figure_does():
    """watch prints a run's events with its summary: each clutch's switches, as the figure's title says them (the
    summary alone gives its first lock only)."""
    from hoistsim.cli.watching import _headline

    summary = {"clutch1_lockup_time": 0.791, "clutch1_slip_energy": 29.5}
    events = {"time": np.array([0.791, 0.831, 1.251]), "kind": np.array(["lock", "unlock", "disengage"], dtype=object),
              "element": np.array(["clutch1"] * 3, dtype=object)}
    assert _headline(summary, events) == ["clutch1 locks at 0.791 s, lets go 0.831 s, opens 1.251 s, 29.5 J of heat"]
    assert _headline(summary) == ["clutch1 first locks at 0.791 s, 29.5 J of heat"]

"""The command line on shipped scenarios: run, --set, check, plot."""

from __future__ import annotations

import os
import subprocess
import sys

import h5py
import pytest
from click.testing import CliRunner
from helpers import ROOT, SCENARIOS

from hoistsim.cli import main


@pytest.mark.slow
def test_cold_run_from_a_fresh_process(tmp_path):
    """`hoistsim run` as a user types it: exit 0, a table on stdout, the file in place."""
    out = tmp_path / "exercise6.h5"
    env = dict(os.environ, HOISTSIM_CACHE_DIR=str(tmp_path / "cache"))
    proc = subprocess.run(
        [sys.executable, "-m", "hoistsim.cli", "run", str(SCENARIOS / "exercise6_direct_start.yaml"), "-o", str(out)],
        capture_output=True, text=True, env=env, cwd=ROOT,
    )
    assert proc.returncode == 0, proc.stderr
    assert "exercise6-direct-start" in proc.stdout and f"wrote {out}" in proc.stdout
    with h5py.File(out, "r") as f:
        assert f["runs/lockup_time"][0] == 0.0  # 3201 N holds the stall torque: no slip


@pytest.mark.slow
def test_set_overrides_a_key_and_is_recorded(tmp_path):
    out = tmp_path / "slip.h5"
    result = CliRunner().invoke(main, ["run", str(SCENARIOS / "exercise6_direct_start.yaml"), "-o", str(out),
                                       "--set", "clutch.engagement_force=200 daN", "--set", "simulation.duration=1 s"])
    assert result.exit_code == 0, result.output
    with h5py.File(out, "r") as f:
        group = f["runs"]
        assert group["engagement_force"][0, 0] == pytest.approx(2000.0)
        assert group["time"][-1] == 1.0
        text = f["scenario"][()]
        text = text.decode() if isinstance(text, bytes) else text
        assert "--set clutch.engagement_force" in text


@pytest.mark.slow
def test_sweep_section_gives_one_run_per_value(tmp_path):
    base = (SCENARIOS / "exercise6_direct_start.yaml").read_text()
    path = tmp_path / "sweep.yaml"
    path.write_text(base.replace("duration: 3 s", "duration: 0.5 s")
                    + "sweep:\n  clutch.engagement_force: [1000 N, 2000 N, 3201 N]\n")
    out = tmp_path / "sweep.h5"
    result = CliRunner().invoke(main, ["run", str(path), "-o", str(out)])
    assert result.exit_code == 0, result.output
    with h5py.File(out, "r") as f:
        assert f["runs/motor_speed"].shape[0] == 3 and f["runs/lockup_time"].shape == (3,)
        assert f["runs/label"].asstr()[1] == "clutch.engagement_force=2000 N"


def test_check_prints_the_reduced_model():
    result = CliRunner().invoke(main, ["check", str(SCENARIOS / "exercise6_direct_start.yaml")])
    assert result.exit_code == 0
    assert "J_b" in result.output and "2.141" in result.output and "valid" in result.output


@pytest.mark.slow
@pytest.mark.parametrize("suffix", [".png", ".svg"])
def test_plot_writes_a_figure(tmp_path, suffix):
    out = tmp_path / "run.h5"
    result = CliRunner().invoke(main, ["run", str(SCENARIOS / "engage_at_speed_with_brake.yaml"), "-o", str(out)])
    assert result.exit_code == 0, result.output
    fig = tmp_path / f"fig{suffix}"
    result = CliRunner().invoke(main, ["plot", str(out), "-o", str(fig)])
    assert result.exit_code == 0, result.output
    assert fig.stat().st_size > 10_000


@pytest.mark.slow
def test_chattering_is_a_one_line_error(tmp_path):
    base = (SCENARIOS / "exercise6_direct_start.yaml").read_text()
    table = ", ".join(f"[{k * 0.05} s, {9000 if k % 2 == 0 else 300} N]" for k in range(24))
    path = tmp_path / "chatter.yaml"
    path.write_text(base.replace("engagement_force: 3201 N", f"engagement_force: [{table}]")
                    .replace("mass: 500 kg", "mass: 300 kg").replace("solver: tsit5", "solver: tsit5\n  max_switches: 4"))
    out = tmp_path / "never.h5"
    result = CliRunner().invoke(main, ["run", str(path), "-o", str(out)])
    assert result.exit_code == 1
    said = [line for line in result.output.strip().splitlines() if "compiling the solver" not in line]
    assert "chatters" in result.output and len(said) == 1
    assert not out.exists()


@pytest.mark.parametrize("args", [
    ["run", "DIR", "-o", "out.h5"],
    ["run", "SCENARIO"],
    ["run", "SCENARIO", "-o", "DIR"],
    ["run", "SCENARIO", "-o", "out.png"],  # results are HDF5, whatever the name says
    ["frobnicate"],
])
@pytest.mark.slow
def test_usage_errors_are_one_line(tmp_path, args):
    args = [str(tmp_path) if a == "DIR" else str(SCENARIOS / "exercise6_direct_start.yaml") if a == "SCENARIO"
            else a for a in args]
    proc = subprocess.run([sys.executable, "-m", "hoistsim.cli", *args], capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error:"), proc.stderr
    assert not (tmp_path / "out.h5").exists() and not (tmp_path / "out.png").exists()


def _short_runback(out, env, cwd, notices=None) -> h5py.File:
    """Run half a second of the run-back scenario in a new process; the written file, open.

    ``notices``: a list that receives the lines of stderr saying a compilation is under way.
    """
    proc = subprocess.run([sys.executable, "-m", "hoistsim.cli", "run", str(SCENARIOS / "runback_slipping_clutch.yaml"),
                           "-o", str(out), "--set", "simulation.duration=0.5 s"],
                          capture_output=True, text=True, env=env, cwd=cwd)
    assert proc.returncode == 0, proc.stderr
    if notices is not None:
        notices.append([line for line in proc.stderr.splitlines() if "compiling" in line])
    return h5py.File(out, "r")


@pytest.mark.slow
def test_second_run_loads_the_stored_executable(tmp_path):
    """With the cache on, a run stores its compiled loop; the next process loads it and agrees bit for bit.

    The first says on stderr, in one line, that it compiles; the second, loading, says nothing.  The first
    also leaves a hint naming its program, so the second reads it ahead, while it reads the scenario.
    """
    env = dict(os.environ, HOISTSIM_CACHE_DIR=str(tmp_path / "cache"))
    outputs, notices = [], []
    for i in range(2):
        with _short_runback(tmp_path / f"run{i}.h5", env, ROOT, notices) as f:
            outputs.append(f["runs/slip_speed"][0])
    assert notices == [["hoistsim: compiling the solver for this scene's structure (once; later runs load it)"], []]
    assert len(list((tmp_path / "cache" / "executables").glob("*.bin"))) == 1
    assert len(list((tmp_path / "cache" / "hints").glob("*.json"))) == 1
    assert (outputs[0] == outputs[1]).all()


@pytest.mark.slow
def test_a_command_run_before_whose_scenario_went_bad_ends_at_its_one_line_error(tmp_path):
    """The second time, the command reads its program ahead while it reads the scenario; a bad edit still
    ends in one line naming the key, exit 2, nothing written (and at once: the program being read is left)."""
    env = dict(os.environ, HOISTSIM_CACHE_DIR=str(tmp_path / "cache"))
    scenario = tmp_path / "scene.yaml"
    text = (SCENARIOS / "runback_slipping_clutch.yaml").read_text(encoding="utf-8")
    scenario.write_text(text, encoding="utf-8")
    command = [sys.executable, "-m", "hoistsim.cli", "run", str(scenario), "-o", "out.h5",
               "--set", "simulation.duration=0.2 s"]
    assert subprocess.run(command, capture_output=True, env=env, cwd=tmp_path).returncode == 0
    assert len(list((tmp_path / "cache" / "hints").glob("*.json"))) == 1  # the next one reads ahead
    (tmp_path / "out.h5").unlink()
    bad = text.replace("engagement_force:", "engagement_forse:", 1)
    assert bad != text
    scenario.write_text(bad, encoding="utf-8")
    proc = subprocess.run(command, capture_output=True, text=True, env=env, cwd=tmp_path)
    assert proc.returncode == 2
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("hoistsim: error:") and "engagement_forse" in lines[0], proc.stderr
    assert not (tmp_path / "out.h5").exists()


@pytest.mark.slow
def test_a_changed_source_is_never_served_a_stored_program(tmp_path):
    """The cache key holds a digest of the package's source: edit the physics and the next run rebuilds."""
    import shutil

    package = tmp_path / "tree" / "hoistsim"
    shutil.copytree(ROOT / "hoistsim", package, ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, HOISTSIM_CACHE_DIR=str(tmp_path / "cache"), PYTHONPATH=str(tmp_path / "tree"))

    def heat(tag: str) -> float:
        with _short_runback(tmp_path / f"{tag}.h5", env, tmp_path) as f:
            return float(f["runs/slip_energy"][0])

    original = heat("original")
    clutch = package / "machine" / "elements" / "friction_clutch.py"
    text = clutch.read_text(encoding="utf-8")
    edited = text.replace("return self.friction(x)[1] * self.torque_per_newton", "return 0.5 * self.friction(x)[1] * "
                          "self.torque_per_newton")
    assert edited != text
    clutch.write_text(edited, encoding="utf-8")
    halved = heat("halved")
    assert len(list((tmp_path / "cache" / "executables").glob("*.bin"))) == 2  # a second program, rebuilt
    assert abs(halved - original) > 0.05 * original  # the edit is in the answer, not the stored program
    from hoistsim import _jax

    assert _jax.source_digest(str(package)) != _jax.source_digest(str(ROOT / "hoistsim"))


@pytest.mark.slow
def test_a_program_compiled_again_after_an_edit_that_leaves_it_the_same_is_stored_whole(tmp_path):
    """An edit that changes no equation (a comment) changes the stored program's key, not the program: it is
    compiled again, and the program stored then serves the next process.  (Served by JAX's own cache and
    serialised again, a CPU program built in several modules lost kernels and failed at its first call in
    the next process, which threw it away and compiled again: see hoistsim._jax._own_compile.)"""
    import shutil

    package = tmp_path / "tree" / "hoistsim"
    shutil.copytree(ROOT / "hoistsim", package, ignore=shutil.ignore_patterns("__pycache__"))
    env = dict(os.environ, HOISTSIM_CACHE_DIR=str(tmp_path / "cache"), PYTHONPATH=str(tmp_path / "tree"))
    stored = tmp_path / "cache" / "executables"
    notices, heats = [], []
    for run in range(3):
        if run == 1:
            clutch = package / "machine" / "elements" / "friction_clutch.py"
            clutch.write_text(clutch.read_text(encoding="utf-8") + "\n# an edit that changes no equation\n",
                              encoding="utf-8")
        with _short_runback(tmp_path / f"run{run}.h5", env, tmp_path, notices) as f:
            heats.append(float(f["runs/slip_energy"][0]))
    assert [len(n) for n in notices] == [1, 1, 0]  # compiled, compiled again after the edit, loaded
    assert len(list(stored.glob("*.bin"))) == 2  # neither thrown away after failing to run
    assert heats[0] == heats[1] == heats[2]

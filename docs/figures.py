"""Regenerate the site's figures from the shipped scenarios, with the commands its pages show.

    python docs/figures.py                      # every figure, into docs/ (about 6 minutes on 2 cores)
    python docs/figures.py force_sweep ...      # only these
    python docs/figures.py --output /tmp/figs   # somewhere else
    python docs/figures.py --list               # the figures and what each runs

Each figure is made by the command line (in this process, so the compiled
solvers are shared): `hoistsim run` then `hoistsim plot`, `hoistsim flywheel
--plot`, or the work-precision study's figure redrawn from its CSV (the study
itself is `benchmarks/work_precision.py`, about 20 minutes).
"""

from __future__ import annotations

import argparse
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENARIOS = ROOT / "scenarios"


def hoistsim_command(*args: str) -> None:
    """``hoistsim ARGS`` in this process (its compiled programs kept for the next); a failure raises."""
    from hoistsim.cli import main

    try:
        main.main(args=list(args), prog_name="hoistsim", standalone_mode=False)
    except SystemExit as exc:  # the command line's own failures (exit 2, 3)
        if exc.code:
            raise RuntimeError(f"hoistsim {' '.join(args)}: exit {exc.code}") from None


def _run_and_plot(scenario: str, keep: dict):
    """`hoistsim run` and `hoistsim plot`; keep maps the plot's outputs (by suffix) to figure names."""
    def make(output: Path, work: Path) -> list[Path]:
        results, figure = work / "results.h5", work / "figure.png"
        hoistsim_command("run", str(SCENARIOS / scenario), "-o", str(results))
        hoistsim_command("plot", str(results), "-o", str(figure))
        written = []
        for suffix, name in keep.items():
            shutil.copyfile(work / f"figure{suffix}.png", output / name)
            written.append(output / name)
        return written

    return make


def _flywheel(scenario: str, irregularity: str, name: str):
    def make(output: Path, work: Path) -> list[Path]:
        hoistsim_command("flywheel", str(SCENARIOS / scenario), "--irregularity", irregularity, "--plot", str(output / name))
        return [output / name]

    return make


def _work_precision(output: Path, work: Path) -> list[Path]:
    from hoistsim.studies.work_precision import read_csv, write_figure

    # drawn from the study's kept numbers (benchmarks/work_precision.py measures them, minutes), for the site
    target = output / "work_precision.png"
    write_figure(read_csv(ROOT / "benchmarks" / "results" / "work_precision.csv"), target)
    return [target]


# name -> (what it runs, how to make it); the site shows each from docs/
FIGURES = {
    "first_scenario": ("hoistsim run + plot scenarios/first_scenario.yaml",
                       _run_and_plot("first_scenario.yaml", {"": "first_scenario.png"})),
    "engage_at_speed_with_brake": ("hoistsim run + plot scenarios/engage_at_speed_with_brake.yaml",
                                   _run_and_plot("engage_at_speed_with_brake.yaml",
                                                 {"": "engage_at_speed_with_brake.png"})),
    "lift_and_run_back_through_a_lossy_mesh": (
        "hoistsim run + plot scenarios/lift_and_run_back_through_a_lossy_mesh.yaml",
        _run_and_plot("lift_and_run_back_through_a_lossy_mesh.yaml", {"": "lift_and_run_back_through_a_lossy_mesh.png"})),
    "start_against_a_slipping_brake": ("hoistsim run + plot scenarios/start_against_a_slipping_brake.yaml",
                                       _run_and_plot("start_against_a_slipping_brake.yaml",
                                                     {"": "start_against_a_slipping_brake.png"})),
    "clutch_duty_cycle": ("hoistsim run + plot scenarios/clutch_duty_cycle.yaml",
                          _run_and_plot("clutch_duty_cycle.yaml", {"": "clutch_duty_cycle.png"})),
    "clutch_force_window": ("hoistsim run + plot scenarios/clutch_force_window.yaml (42 forces)",
                            _run_and_plot("clutch_force_window.yaml", {"_summary": "clutch_force_window.png"})),
    "force_sweep": ("hoistsim run + plot scenarios/force_sweep_engage_at_speed.yaml (10 forces)",
                    _run_and_plot("force_sweep_engage_at_speed.yaml",
                                  {"": "force_sweep.png", "_summary": "force_sweep_summary.png"})),
    "lift_off_the_ground": ("hoistsim run + plot scenarios/lift_off_the_ground.yaml",
                            _run_and_plot("lift_off_the_ground.yaml", {"": "lift_off_the_ground.png"})),
    "lift_off_force_sweep": ("hoistsim run + plot scenarios/lift_off_force_sweep.yaml (9 forces)",
                             _run_and_plot("lift_off_force_sweep.yaml", {"_summary": "lift_off_force_sweep.png"})),
    "snatch_from_slack": ("hoistsim run + plot scenarios/snatch_from_slack.yaml",
                          _run_and_plot("snatch_from_slack.yaml", {"": "snatch_from_slack.png"})),
    "load_onto_a_buffer": ("hoistsim run + plot scenarios/load_onto_a_buffer.yaml",
                           _run_and_plot("load_onto_a_buffer.yaml", {"": "load_onto_a_buffer.png"})),
    "coupled_clutches": ("hoistsim run + plot scenarios/coupled_clutches.yaml",
                         _run_and_plot("coupled_clutches.yaml", {"": "coupled_clutches.png"})),
    "two_speed_hoist": ("hoistsim run + plot scenarios/two_speed_hoist.yaml",
                        _run_and_plot("two_speed_hoist.yaml", {"": "two_speed_hoist.png"})),
    "brake_stop_on_an_elastic_rope": ("hoistsim run + plot scenarios/brake_stop_on_an_elastic_rope.yaml",
                                      _run_and_plot("brake_stop_on_an_elastic_rope.yaml",
                                                    {"": "brake_stop_on_an_elastic_rope.png"})),
    "slider_crank_periodic": ("hoistsim run + plot scenarios/slider_crank_press.yaml",
                              _run_and_plot("slider_crank_press.yaml", {"_periodic": "slider_crank_periodic.png"})),
    "engine_periodic": ("hoistsim run + plot scenarios/engine_hoist_flywheel.yaml (about 40 s)",
                        _run_and_plot("engine_hoist_flywheel.yaml", {"_periodic": "engine_periodic.png"})),
    "engine_flywheel": ("hoistsim flywheel scenarios/engine_hoist_flywheel.yaml --irregularity 0.02 (about 4 min)",
                        _flywheel("engine_hoist_flywheel.yaml", "0.02", "engine_flywheel.png")),
    "dcpm_start": ("hoistsim run + plot scenarios/modelica/DCPM_Start.yaml",
                   _run_and_plot("modelica/DCPM_Start.yaml", {"": "dcpm_start.png"})),
    "pid_controller": ("hoistsim run + plot scenarios/modelica/PID_Controller.yaml",
                       _run_and_plot("modelica/PID_Controller.yaml", {"": "pid_controller.png"})),
    "oscillator": ("hoistsim run + plot scenarios/modelica/translational/Oscillator.yaml",
                   _run_and_plot("modelica/translational/Oscillator.yaml", {"": "oscillator.png"})),
    "imc_dol": ("hoistsim run + plot scenarios/modelica/IMC_DOL.yaml",
                _run_and_plot("modelica/IMC_DOL.yaml", {"": "imc_dol.png"})),
    "imc_yd": ("hoistsim run + plot scenarios/modelica/IMC_YD.yaml",
               _run_and_plot("modelica/IMC_YD.yaml", {"": "imc_yd.png"})),
    "inverter_hoist_brake_sequence": ("hoistsim run + plot scenarios/inverter_hoist_brake_sequence.yaml",
                                      _run_and_plot("inverter_hoist_brake_sequence.yaml",
                                                    {"": "inverter_hoist_brake_sequence.png"})),
    "emergency_stop_lowering": ("hoistsim run + plot scenarios/emergency_stop_lowering.yaml",
                                _run_and_plot("emergency_stop_lowering.yaml", {"": "emergency_stop_lowering.png"})),
    "compliant_hoist": ("hoistsim run + plot scenarios/compliant_hoist.yaml",
                        _run_and_plot("compliant_hoist.yaml", {"": "compliant_hoist.png"})),
    "work_precision": ("the work-precision figure, redrawn from benchmarks/results/work_precision.csv",
                       _work_precision),
}


def regenerate(names=None, output: Path = ROOT / "docs", progress=print) -> list[Path]:
    """Make the named figures (all when None) in ``output``; returns the files written."""
    names = list(FIGURES) if not names else list(names)
    unknown = [n for n in names if n not in FIGURES]
    if unknown:
        raise KeyError(f"no figure named {', '.join(unknown)}: choose from {', '.join(FIGURES)}")
    output = Path(output)
    output.mkdir(parents=True, exist_ok=True)
    written = []
    for name in names:
        started = time.perf_counter()
        with tempfile.TemporaryDirectory() as work:
            made = FIGURES[name][1](output, Path(work))
        written += made
        progress(f"{name}: {', '.join(str(p) for p in made)} ({time.perf_counter() - started:.1f} s)")
    return written


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("names", nargs="*", help="figures to make (default: all)")
    parser.add_argument("--output", default=str(ROOT / "docs"), help="folder for the figures (default docs/)")
    parser.add_argument("--list", action="store_true", help="list the figures and what each runs")
    args = parser.parse_args()
    if args.list:
        for figure, (what, _) in FIGURES.items():
            print(f"{figure:32s} {what}")
        sys.exit(0)
    try:
        regenerate(args.names, Path(args.output))
    except (KeyError, RuntimeError) as exc:
        print(f"figures: {exc.args[0]}", file=sys.stderr)
        sys.exit(2)

"""Where a sweep's time goes, stage by stage, and whether each stage grows linearly with the runs.

The engagement-force sweep of scenarios/force_sweep_engage_at_speed.yaml
(--sweep FROM:TO:COUNT), summary-only and with full output, at growing counts;
each stage timed apart, warm (the best of two for the sweeps: the first call of a new chunk shape
compiles), in this process:

- load: reading the scenario and validating the base and every swept value;
- runs: one (label, scenario) per run (sweep_values);
- plans: the traced inputs of every run (build_plan);
- sweep: hoistsim.sweep end to end, summaries only (includes the plans) and, up
  to FULL_MAX runs, with every time series streamed to an HDF5 file.

    python benchmarks/sweep_stages.py               # 1e3, 1e4 (and full output at 1e3)
    python benchmarks/sweep_stages.py --large       # adds 1e5
"""

from __future__ import annotations

import argparse
import resource
import tempfile
import time
from pathlib import Path

from hoistsim import load_scenario, sweep
from hoistsim.machine.assemble import build_plan
from hoistsim.results.report import table
from hoistsim.scenario.sweep_runs import sweep_values

SCENARIO = Path(__file__).resolve().parents[1] / "scenarios" / "force_sweep_engage_at_speed.yaml"
FULL_MAX = 1000


def timed(func, repeats: int = 1):
    """The best of ``repeats`` calls (the first may compile a new chunk shape), and the last value."""
    best = float("inf")
    for _ in range(repeats):
        start = time.perf_counter()
        value = func()
        best = min(best, time.perf_counter() - start)
    return best, value


def main(counts) -> None:
    sweep(load_scenario(SCENARIO, sweeps=["clutch.engagement_force=3 kN:12 kN:8"]), summary_only=True)  # compile
    sweep(load_scenario(SCENARIO, sweeps=["clutch.engagement_force=3 kN:12 kN:8"]))
    rows = []
    for count in counts:
        spec = [f"clutch.engagement_force=3 kN:12 kN:{count}"]
        load, scenario = timed(lambda: load_scenario(SCENARIO, sweeps=spec))
        runs_time, pairs = timed(lambda: sweep_values(scenario))
        plans_time, _ = timed(lambda: [build_plan(s, summary_only=True) for _, s in pairs])
        summary_time, _ = timed(lambda: sweep(scenario, summary_only=True), repeats=2)
        full = float("nan")
        if count <= FULL_MAX:
            with tempfile.TemporaryDirectory() as folder:
                full, _ = timed(lambda: sweep(scenario, output=Path(folder) / "full.h5"), repeats=2)
        per = 1e6 / count
        rows.append([f"{count:,}", f"{load * per:.0f}", f"{runs_time * per:.0f}", f"{plans_time * per:.0f}",
                     f"{summary_time * per:.0f}", f"{full * per:.0f}" if full == full else "-",
                     f"{resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024:.0f}"])
    print(table(["runs", "load [us/run]", "runs [us/run]", "plans [us/run]", "sweep, summaries [us/run]",
                 "sweep, full output to a file [us/run]", "peak RSS [MiB]"], rows, align="rrrrrrr"))


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--large", action="store_true", help="add 100 000 runs")
    args = parser.parse_args()
    main([1000, 10000] + ([100000] if args.large else []))

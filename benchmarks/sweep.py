"""What a sweep costs: hoistsim's vectorised sweep against a scipy solve_ivp loop.

The scenario is scenarios/force_sweep_engage_at_speed.yaml (motor idling at
300 rpm, clutch closed on a 500 kg load; weak forces let the load run back,
strong ones slip then lock), with the engagement force swept over 3-12 kN at
1, 100, 1 000 and 10 000 values.  Both sides run the same hybrid model at the
same tolerances (rtol 1e-8, atol 1e-10):

- hoistsim: `hoistsim.sweep(..., summary_only=True)`, every run through one
  compiled, vmapped restart loop; compiled first (compile time reported apart),
  then timed (median of repeats).  Full time series are timed up to 1 000 values.
- scipy: hoistsim.scipy_reference.solve_with_scipy, a plain Python loop of
  solve_ivp (RK45) with terminal events and restarts, no dense output.  Timed
  per scenario on up to 200 evenly spaced scenarios of the same sweep; beyond
  that its total is that per-scenario cost times the count (marked "est.").

Agreement of the two on lock-up time and clutch energy is printed too, so the
comparison is at equal accuracy.  Peak memory is the process's peak RSS.

    python benchmarks/sweep.py            # the table for benchmarks/README.md
    python benchmarks/sweep.py --quick    # 1 and 100 values only
"""

from __future__ import annotations

import argparse
import math
import resource
import statistics
import time
from pathlib import Path

import numpy as np

import hoistsim
from hoistsim import load_scenario
from hoistsim.report import table
from hoistsim.scenario import sweep_values
from hoistsim.scipy_reference import solve_scenario_with_scipy

SCENARIO = Path(__file__).resolve().parents[1] / "scenarios" / "force_sweep_engage_at_speed.yaml"
SCIPY_SAMPLE = 200


def scenario_with(count: int):
    return load_scenario(SCENARIO, sweeps=[f"clutch.engagement_force=3 kN:12 kN:{count}"])


def timed(func, repeats: int) -> tuple[float, float]:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return statistics.median(times), min(times)


def peak_rss_mib() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def scipy_cost(scenario, count: int) -> tuple[float, int, dict]:
    """Median seconds per scenario of the scipy loop, the sample size, and its answers."""
    pairs = sweep_values(scenario)
    picks = np.unique(np.linspace(0, count - 1, min(count, SCIPY_SAMPLE)).round().astype(int))
    seconds, answers = [], {}
    for i in picks:
        start = time.perf_counter()
        events, _, pieces, _ = solve_scenario_with_scipy(pairs[i][1], method="RK45")
        seconds.append(time.perf_counter() - start)
        locks = [t for t, kind in events if kind == "lock"]
        answers[int(i)] = (locks[0] if locks else math.nan, pieces)
    return statistics.median(seconds), len(picks), answers


def agreement(result, answers) -> float:
    """Largest lock-up time difference (s) between hoistsim and scipy over the sampled runs."""
    worst = 0.0
    for i, (lock, _) in answers.items():
        ours = result.summaries[i]["lockup_time"]
        if math.isnan(lock) or math.isnan(ours):
            assert math.isnan(lock) and math.isnan(ours), (i, lock, ours)
            continue
        worst = max(worst, abs(ours - lock))
    return worst


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="1 and 100 values only")
    args = parser.parse_args()
    counts = [1, 100] if args.quick else [1, 100, 1000, 10000]
    rows = []
    for count in counts:
        scenario = scenario_with(count)
        repeats = 5 if count <= 1000 else 3
        cold = time.perf_counter()
        result = hoistsim.sweep(scenario, summary_only=True)  # compiles (or reuses) the loop
        first = time.perf_counter() - cold
        warm, best = timed(lambda: hoistsim.sweep(scenario, summary_only=True), repeats)
        full = "-"
        if count <= 1000:
            hoistsim.sweep(scenario)  # compile the full-output shape
            full_warm, _ = timed(lambda: hoistsim.sweep(scenario), 3)
            full = f"{full_warm / count * 1e3:.3f}"
        per_scipy, sample, answers = scipy_cost(scenario, count)
        rows.append([
            f"{count:,}",
            f"{max(first - warm, 0.0):.2f}",
            f"{warm:.3f}",
            f"{warm / count * 1e3:.3f}",
            full,
            f"{per_scipy * count:.2f}" + ("" if sample == count else " est."),
            f"{per_scipy * 1e3:.2f}",
            f"{per_scipy / (warm / count):.0f}x",
            f"{agreement(result, answers):.1e}",
            f"{peak_rss_mib():.0f}",
        ])
        print(f"  {count} values done", flush=True)
    print()
    print(table(["values", "compile [s]", "hoistsim warm [s]", "per run [ms]", "per run, full output [ms]",
                 "scipy loop [s]", "scipy per run [ms]", "ratio", "lock-up diff [s]", "peak RSS [MiB]"],
                rows))
    print(f"\nscipy timed on up to {SCIPY_SAMPLE} evenly spaced scenarios per row; "
          "ratio = scipy per run / hoistsim summary-only per run.")


if __name__ == "__main__":
    main()

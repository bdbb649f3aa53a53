"""What the elastic rope costs a run: the lift-off force sweep against the same sweep with a rigid rope, vmapped.

The scene is `scenarios/lift_off_force_sweep.yaml` (500 kg resting on 20 m of wire rope, the clutch closed
on the motor idling at 300 rpm, 2 s): as shipped (the wire rope, the ground, HC2), with a rigid rope on
the ground (`rope:` removed: the load rests until the drive lifts it), and with a rigid rope and the load
hanging from the start (`rope:` and `ground:` removed: the canonical engagement).  The same engagement
forces (4 to 20 kN), summary-only and with full output (every series on the 1 ms grid), in process; each
compiled first, then the median of five, interleaved.  The rope adds an oscillation of ~5 Hz that every
run follows to the end, so the steps, passes and switches a run are shown too (full-output runs).

    python benchmarks/rope_cost.py [--runs 1000]
"""

from __future__ import annotations

import argparse
import statistics
from pathlib import Path

from elements_cost import per_run

from hoistsim import load_scenario, sweep
from hoistsim.results.report import table

SCENARIO = Path(__file__).resolve().parents[1] / "scenarios" / "lift_off_force_sweep.yaml"
RIGID = "rigid rope, on the ground"


def scenes(runs: int) -> dict:
    shipped = load_scenario(SCENARIO, sweeps=[f"clutch.engagement_force=4 kN:20 kN:{runs}"])
    return {"rigid rope, hanging": shipped.model_copy(update={"rope": None, "ground": None}),
            RIGID: shipped.model_copy(update={"rope": None}),
            "wire rope, on the ground": shipped}


def story(scenario) -> dict:
    """Median steps, rejected steps, passes and switches a run (full output keeps each run's counters)."""
    runs = sweep(scenario).runs
    return {key: statistics.median(run.stats[key] for run in runs)
            for key in ("steps", "rejected_steps", "segments", "switches")}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1000)
    runs = parser.parse_args().runs
    built = scenes(runs)
    stories = {name: story(scenario) for name, scenario in built.items()}
    rows = []
    for label, options in (("summary-only", {"summary_only": True}), ("full output", {})):
        cost = per_run(built, runs, **options)
        for name in built:
            told = stories[name]
            rows.append([label, name, f"{cost[name]:.0f}", f"{cost[name] / cost[RIGID]:.2f}x",
                         f"{told['steps']:.0f}", f"{told['rejected_steps']:.0f}", f"{told['segments']:.0f}",
                         f"{told['switches']:.0f}"])
    print(f"{runs} runs a sweep, in process, medians of 5 after compiling; steps etc.: medians over the runs")
    print(table(["output", "scene", "us/run", "against rigid", "steps", "rejected", "passes", "switches"],
                rows, align="llrrrrrr"))


if __name__ == "__main__":
    main()

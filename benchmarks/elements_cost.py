"""What every friction element at once costs a run, against the canonical scene, vmapped (one run).

The canonical scene is `scenarios/engage_at_speed_with_brake.yaml` (motor run up, the drum held by a
holding brake, the clutch ramped on, the brake released at 0.6 s).  The same scene with all the
friction elements: the brake made a friction brake (static 3 kN*m, kinetic 2 kN*m) applied again at
2.5 s, a pawl on the drum, and a lossy mesh (efficiency 0.95, backdrive 0.9).  Both sweep the same
engagement forces (the last value of the clutch's force table), summary-only and with full output,
in process; each compiled first, then the median of three.  The goal: within 2x of the canonical scene.

    python benchmarks/elements_cost.py [--runs 2048]
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from hoistsim import load_scenario, sweep
from hoistsim.report import table

SCENARIO = Path(__file__).resolve().parents[1] / "scenarios" / "engage_at_speed_with_brake.yaml"
ALL_ELEMENTS = ["brake.static_torque=3000 N*m", "brake.kinetic_torque=2000 N*m", "brake.apply_time=2.5 s",
                "gears.efficiency=0.95", "gears.backdrive_efficiency=0.9"]


def scene(extra: list[str], runs: int):
    forces = ", ".join(f"[[0 s, 0 N], [0.5 s, 0 N], [0.6 s, {3000 + 9000 * i / (runs - 1):.3f} N]]"
                       for i in range(runs))
    scenario = load_scenario(SCENARIO, overrides=extra, sweeps=[f"clutch.engagement_force=[{forces}]"])
    if extra:  # a pawl too: `ratchet: {}` is a section, not a key to set
        from hoistsim.schema import RatchetSpec
        scenario = scenario.model_copy(update={"ratchet": RatchetSpec()})
    return scenario


def per_run(scenario, runs: int, **options) -> float:
    sweep(scenario, **options)  # compile
    times = []
    for _ in range(3):
        started = time.perf_counter()
        sweep(scenario, **options)
        times.append(time.perf_counter() - started)
    return statistics.median(times) / runs * 1e6


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=2048)
    runs = parser.parse_args().runs
    rows = []
    for label, options in (("summary-only", {"summary_only": True}), ("full output", {})):
        canonical = per_run(scene([], runs), runs, **options)
        every = per_run(scene(ALL_ELEMENTS, runs), runs, **options)
        rows.append([label, f"{canonical:.0f}", f"{every:.0f}", f"{every / canonical:.2f}x"])
    print(f"{runs} runs a sweep, in process, medians of 3 after compiling")
    print(table(["output", "canonical [us/run]", "all elements [us/run]", "ratio"], rows, align="lrrr"))


if __name__ == "__main__":
    main()

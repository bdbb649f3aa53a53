"""What every friction element at once costs a run, against the canonical scene, vmapped (one run).

The canonical scene is `scenarios/engage_at_speed_with_brake.yaml` (motor run up, the drum held by a
holding brake, the clutch ramped on, the brake released at 0.6 s).  The same start with every friction
element: the brake made a friction brake (static 3 kN*m, kinetic 2 kN*m), a pawl on the drum, and a
lossy mesh (efficiency 0.95, backdrive 0.9): the same story, as many passes and steps.  And that scene
with the brake applied again at 2.5 s, which catches the rising drum: a longer story (7 passes, not 5).
All sweep the same engagement forces (the last value of the clutch's force table), summary-only and
with full output, in process; each compiled first, then the median of five, interleaved.  The goal:
within 2x of the canonical scene.

    python benchmarks/elements_cost.py [--runs 1024]
"""

from __future__ import annotations

import argparse
import statistics
import time
from pathlib import Path

from hoistsim import load_scenario, sweep
from hoistsim.results.report import table

SCENARIO = Path(__file__).resolve().parents[1] / "scenarios" / "engage_at_speed_with_brake.yaml"
ALL_ELEMENTS = ["brake.static_torque=3000 N*m", "brake.kinetic_torque=2000 N*m",
                "gears.efficiency=0.95", "gears.backdrive_efficiency=0.9"]
APPLIED_AGAIN = ALL_ELEMENTS + ["brake.apply_time=2.5 s"]


def scene(extra: list[str], runs: int):
    forces = ", ".join(f"[[0 s, 0 N], [0.5 s, 0 N], [0.6 s, {3000 + 9000 * i / (runs - 1):.3f} N]]"
                       for i in range(runs))
    scenario = load_scenario(SCENARIO, overrides=extra, sweeps=[f"clutch.engagement_force=[{forces}]"])
    if extra:  # a pawl too: `ratchet: {}` is a section, not a key to set
        from hoistsim.scenario.schema import RatchetSpec
        scenario = scenario.model_copy(update={"ratchet": RatchetSpec()})
    return scenario


def per_run(scenes: dict, runs: int, repeats: int = 5, **options) -> dict:
    """Microseconds a run of each scene's sweep: compiled first, then the median of interleaved repeats."""
    for scenario in scenes.values():
        sweep(scenario, **options)  # compile
    times: dict = {name: [] for name in scenes}
    for _ in range(repeats):
        for name, scenario in scenes.items():
            started = time.perf_counter()
            sweep(scenario, **options)
            times[name].append(time.perf_counter() - started)
    return {name: statistics.median(spent) / runs * 1e6 for name, spent in times.items()}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1024)
    runs = parser.parse_args().runs
    scenes = {"canonical": scene([], runs), "every element": scene(ALL_ELEMENTS, runs),
              "every element, brake applied again": scene(APPLIED_AGAIN, runs)}
    rows = []
    for label, options in (("summary-only", {"summary_only": True}), ("full output", {})):
        cost = per_run(scenes, runs, **options)
        for name in list(scenes)[1:]:
            rows.append([label, name, f"{cost['canonical']:.0f}", f"{cost[name]:.0f}",
                         f"{cost[name] / cost['canonical']:.2f}x"])
    print(f"{runs} runs a sweep, in process, medians of 5 after compiling")
    print(table(["output", "scene", "canonical [us/run]", "scene [us/run]", "ratio"], rows, align="llrrr"))


if __name__ == "__main__":
    main()

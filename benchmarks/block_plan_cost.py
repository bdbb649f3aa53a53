"""What a sweep's plans cost a run: a block's plans built from its first run's (``block_plans``: only the parts a
swept key reaches written out again and built), against every run's plan built in full, in the same process.

Nothing is compiled or run: this is the host's work before a block's compiled call, which a large sweep pays for
every run.  Each sweep is a block of RUNS runs (a summary-only sweep's block on one device); the median of
REPEATS; "path" says how the block's reached elements were built (``stacked``: once for the whole block from its
values stacked; ``listed``: run by run; ``full``: the block falls back to building every plan in full, and its
cost is that).

    python benchmarks/block_plan_cost.py
"""

from __future__ import annotations

import statistics
import time
from pathlib import Path

from hoistsim import load_scenario
from hoistsim.machine.assemble import build_plan
from hoistsim.results.report import table
from hoistsim.running import block_plans as bp
from hoistsim.scenario.sweep_runs import SweepRuns

SCENARIOS = Path(__file__).resolve().parents[1] / "scenarios"
RUNS = 2048
REPEATS = 5

# (what is swept, scenario, the sweep)
SWEEPS = [
    ("hoist: engagement force", "force_sweep_engage_at_speed.yaml", "clutch.engagement_force=3 kN:12 kN:{n}"),
    ("hoist: gear wheel inertia", "engage_at_speed_with_brake.yaml", "gears.wheel_inertia=0.1 kg*m^2:3 kg*m^2:{n}"),
    ("hoist: starting speed", "force_sweep_engage_at_speed.yaml", "initial.motor_speed=100 rpm:300 rpm:{n}"),
    ("hoist at its steady lift: load", "exercise6_constant_speed.yaml", "load.mass=100 kg:800 kg:{n}"),
    ("hoist: force tables", "engage_at_speed_with_brake.yaml", None),
    ("drawn: a shaft's inertia", "coupled_clutches.yaml", "drivetrain.shafts.J1.inertia=0.5 kg*m^2:2 kg*m^2:{n}"),
    ("drawn: a clutch's friction", "coupled_clutches.yaml", "drivetrain.clutches.clutch2.kinetic_friction=0.2:0.5:{n}"),
]


def _tables(n: int) -> str:
    """``n`` engagement-force tables of two lengths (they do not stack: built run by run)."""
    tables = [f"[[0 s, 0 N], [0.5 s, 0 N], [0.6 s, {3000 + 10 * k} N]]" if k % 2 else
              f"[[0 s, 0 N], [0.3 s, 1 kN], [0.4 s, 1 kN], [0.6 s, {3000 + 10 * k} N]]" for k in range(n)]
    return "clutch.engagement_force=[" + ", ".join(tables) + "]"


def _median(func) -> float:
    times = []
    for _ in range(REPEATS):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    rows = []
    for what, name, spec in SWEEPS:
        sweep = _tables(RUNS) if spec is None else spec.format(n=RUNS)
        runs = SweepRuns(load_scenario(SCENARIOS / name, sweeps=[sweep]))
        indices = list(range(RUNS))
        plans = bp.block_plans(runs, indices)
        path = "full" if plans is None else "stacked" if all(
            isinstance(c, bp.StackedElements) for c in plans.rebuilt.values()) else "listed"
        block = _median(lambda: bp.block_plans(runs, indices))
        scenarios = [runs.scenario(i) for i in indices]
        full = _median(lambda: [build_plan(s, summary_only=True) for s in scenarios])
        block += full if plans is None else 0.0
        rows.append([what, path, f"{1e6 * block / RUNS:.0f}", f"{1e6 * full / RUNS:.0f}", f"{full / block:.1f}"])
    print(f"{RUNS} runs a block, median of {REPEATS}")
    print(table(["sweep", "path", "block's plans [us/run]", "each plan in full [us/run]", "ratio"], rows,
                align="llrrr"))


if __name__ == "__main__":
    main()

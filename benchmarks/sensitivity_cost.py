"""What a sensitivity costs: n keys' derivatives against one warm run of the same scene, measured in one process.

For each scene and each count of keys n: the compile of the derivative's program (one a structure and
count), the warm derivative's compiled call alone and the whole ``hoistsim.sensitivity`` call (the
plans built either side of each key's value, the readout), each against the warm compiled call of the
same scene's summary-only run (the lean loop the derivative differentiates); medians of REPEATS after a
first call.  The goal: the derivative of n keys costs at most (1 + n) warm runs.

    python benchmarks/sensitivity_cost.py          # about 3 min on 2 cores
"""

from __future__ import annotations

import functools
import statistics
import sys
import time
from pathlib import Path

import jax
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from hoistsim import load_scenario  # noqa: E402
from hoistsim.machine.assemble import build_plan  # noqa: E402
from hoistsim.machine.core.loop import SOLVERS, restart_loop  # noqa: E402
from hoistsim.results.report import table  # noqa: E402
from hoistsim.running import sensitivity as sens  # noqa: E402

REPEATS = 15
SCENES = {
    "engage at speed (one lock)": ("engage_at_speed_with_brake.yaml",
                                   ["clutch.kinetic_friction", "load.mass", "motor.inertia", "clutch.static_friction",
                                    "drum.inertia"]),
    "lift-off on a rope": ("lift_off_the_ground.yaml",
                           ["load.mass", "rope.modulus", "clutch.kinetic_friction", "motor.inertia", "drum.inertia"]),
    "CoupledClutches": ("coupled_clutches.yaml",
                        [f"drivetrain.clutches.clutch{k}.kinetic_friction" for k in (1, 2, 3)]
                        + ["drivetrain.shafts.J2.inertia", "drivetrain.shafts.J3.inertia"]),
}


def median_seconds(call) -> float:
    call()
    times = []
    for _ in range(REPEATS):
        started = time.perf_counter()
        jax.block_until_ready(call())
        times.append(time.perf_counter() - started)
    return statistics.median(times)


def main() -> None:
    rows = []
    for name, (file, keys) in SCENES.items():
        scenario = load_scenario(ROOT / "scenarios" / file)
        plan, _ = build_plan(scenario, summary_only=True)
        solver = SOLVERS[scenario.simulation.solver]()
        lean = jax.jit(functools.partial(restart_loop, solver=solver, log_size=1, step_room=0, columns=False))
        run = median_seconds(lambda: lean(plan).scalars)
        for n in (1, 3, 5):
            wrt = keys[:n]
            directions = [sens.plan_direction(scenario, key, sens.key_value(scenario, key), plan) for key in wrt]
            stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *directions)
            program = sens._program(scenario.simulation.solver, 1, 0, False)  # the summaries' program
            started = time.perf_counter()
            program.lower(plan, stacked).compile()
            compile_s = time.perf_counter() - started
            compiled = median_seconds(lambda: program(plan, stacked))
            whole = median_seconds(lambda: sens.sensitivity(scenario, wrt, None).values)
            rows.append([name, str(n), f"{compile_s:.1f}", f"{run * 1e3:.2f}", f"{compiled * 1e3:.2f}",
                         f"{compiled / run:.2f}", f"{whole * 1e3:.2f}", f"{whole / run:.2f}", f"{1 + n}"])
            print(f"  {name}, {n} keys: {compiled / run:.2f} runs (whole call {whole / run:.2f})", flush=True)
    print(table(["scene", "keys", "compile [s]", "run [ms]", "derivatives [ms]", "in runs", "whole call [ms]",
                 "in runs", "goal"], rows))


if __name__ == "__main__":
    main()

"""What a sensitivity costs: n keys' derivatives against one warm run of the same scene, measured in one process.

For each scene and each count of keys n: the compile of the derivative's program (one a structure and
count), the warm derivative's compiled call alone and the whole ``hoistsim.sensitivity`` call (the
plans built either side of each key's value, the readout), each against the warm compiled call of the
same scene's summary-only run (the lean loop the derivative differentiates); medians of REPEATS after a
first call.  The goal: the derivative of n keys costs at most (1 + n) warm runs.

With ``--sweep``: every run of a 256-run sweep (the engagement-force sweep of engage at speed) differentiated
with respect to three sets of keys (:func:`hoistsim.sensitivity` on the sweep: a compiled call a chunk of
runs), per run against the same sweep's warm summary-only run per run (:func:`hoistsim.sweep`): the compiled
calls alone, and the whole call.

    python benchmarks/sensitivity_cost.py          # about 3 min on 2 cores
    python benchmarks/sensitivity_cost.py --sweep  # about 2 min
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
from hoistsim.running import derivative_program, key_directions  # noqa: E402
from hoistsim.running import sensitivity as sens  # noqa: E402
from hoistsim.running import sweep_sensitivity as ss  # noqa: E402

REPEATS = 15 if "--sweep" not in sys.argv[1:] else 5
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
            directions = [key_directions.plan_direction(scenario, key, key_directions.key_value(scenario, key), plan)
                          for key in wrt]
            stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *directions)
            program = derivative_program._program(scenario.simulation.solver, 1, 0, False)  # the summaries' program
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


SWEPT_RUNS = 256
# keys whose elements no swept key reaches (their direction is found once); keys of the swept clutch (the plans
# either side of their value built for every run at once, from the template); the swept key itself (each run's
# direction from its own plans either side, built in full)
SWEPT_KEYS = {"load, motor": ["load.mass", "motor.inertia"],
              "clutch frictions, load": ["clutch.kinetic_friction", "clutch.static_friction", "load.mass"],
              "the swept force": ["clutch.engagement_force"]}


def sweep_main() -> None:
    import tempfile

    from hoistsim import sweep

    text = (ROOT / "scenarios" / "force_sweep_engage_at_speed.yaml").read_text(encoding="utf-8")
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "sweep.yaml"
        path.write_text(text.replace("count: 10}", f"count: {SWEPT_RUNS}}}"), encoding="utf-8")
        scenario = load_scenario(path)
    run = median_seconds(lambda: sweep(scenario, summary_only=True).summary["slip_energy"]) / SWEPT_RUNS
    rows = []
    for name, wrt in SWEPT_KEYS.items():
        started = time.perf_counter()
        sens.sensitivity(scenario, wrt)
        first = time.perf_counter() - started
        results = ss._results
        compiled = [0.0]

        def timed(chunks, width):  # the compiled calls' share of the whole call (the chunks' inputs made apart)
            inputs = list(chunks)
            calls = results(iter(inputs), width)
            while True:
                started = time.perf_counter()
                item = next(calls, None)
                compiled[0] += time.perf_counter() - started
                if item is None:
                    return
                yield item

        ss._results = timed
        compiled[0] = 0.0
        whole = median_seconds(lambda: sens.sensitivity(scenario, wrt).values) / SWEPT_RUNS
        calls = compiled[0] / (REPEATS + 1) / SWEPT_RUNS
        ss._results = results
        n = len(wrt)
        rows.append([name, str(n), f"{first:.1f}", f"{run * 1e6:.0f}", f"{calls * 1e6:.0f}", f"{calls / run:.2f}",
                     f"{whole * 1e6:.0f}", f"{whole / run:.2f}", f"{1 + n}"])
        print(f"  {name}: {whole / run:.2f} runs a run", flush=True)
    print(f"{SWEPT_RUNS} runs of force_sweep_engage_at_speed.yaml, per run (medians of {REPEATS})")
    print(table(["keys", "n", "first call [s]", "summary-only run [us]", "compiled calls [us]", "in runs",
                 "whole call [us]", "in runs", "goal"], rows))


if __name__ == "__main__":
    sweep_main() if "--sweep" in sys.argv[1:] else main()

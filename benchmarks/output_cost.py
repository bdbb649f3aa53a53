"""What full output costs beside summaries only: the compiled loop alone, one vmapped chunk, per run.

The engagement-force sweep of scenarios/force_sweep_engage_at_speed.yaml (2 s, rtol 1e-8, every series
on its 1 ms grid: 2 001 rows) as one chunk of N runs (default 256), through the loop a sweep compiles
(`hoistsim.running.blocks.compiled_batch`, one device): summary-only (the lean loop: no rows, an event log of
one row) against full output (the rows written from each step's interpolant, the event rows, every
output column at every row).  Each program compiled first (compile time shown), then 7 rounds with the
two calls interleaved; medians and minima.  Host work (plans, reading the results back, the file) is
left out: this is what the engine itself pays for the rows.

With ``--against COMMIT`` the same measurement runs in a worktree of that commit, in a process of its
own right after this tree's, so that the columns come from the same minutes.

    python benchmarks/output_cost.py [--runs 256] [--against e9cbcd6]
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = "scenarios/force_sweep_engage_at_speed.yaml"
PROGRAM = r"""
import json, os, statistics, sys, time
sys.path.insert(0, {root!r})
os.environ["HOISTSIM_CACHE_DIR"] = ""
import numpy as np
import hoistsim._jax  # noqa: F401
import jax
from hoistsim import load_scenario
from hoistsim.machine import assemble
from hoistsim.machine.assemble import build_plan
from hoistsim.running.blocks import compiled_batch
from hoistsim.scenario.sweep_runs import sweep_values

runs = [s for _, s in sweep_values(load_scenario(os.path.join({root!r}, {scenario!r}),
                                                 sweeps=["clutch.engagement_force=3 kN:12 kN:{runs}"]))]
calls, out = {{}}, {{}}
for name, summary_only in (("summary-only", True), ("full output", False)):
    plans = [build_plan(s, summary_only=summary_only)[0] for s in runs]
    if hasattr(assemble, "step_room"):  # the loop's static sizes, as the tree measured has them
        sizes = (1, 1) if summary_only else (assemble.log_rows(plans[0]), assemble.step_room(plans[0], sweep=True))
    elif hasattr(assemble, "log_rows"):
        sizes = (1,) if summary_only else (assemble.log_rows(plans[0]),)
    else:
        sizes = assemble.loop_sizes(plans[0], runs[0].simulation.max_switches)
        sizes = (sizes[0], 1) if summary_only else sizes
    stacked = jax.tree.map(lambda *leaves: np.stack(leaves), *plans)
    started = time.perf_counter()
    program = compiled_batch(runs[0].simulation.solver, *sizes, not summary_only, 1).lower(stacked).compile()
    out[name] = dict(compile=time.perf_counter() - started, rows=int(plans[0].grid.shape[0]))
    jax.block_until_ready(program(stacked))
    calls[name] = (program, stacked, [])
for _ in range(7):
    for program, stacked, times in calls.values():
        started = time.perf_counter()
        jax.block_until_ready(program(stacked))
        times.append((time.perf_counter() - started) / {runs} * 1e6)
for name, (_, _, times) in calls.items():
    out[name].update(median=statistics.median(times), min=min(times))
print(json.dumps(out))
"""


def measure(root: Path, runs: int) -> dict:
    code = PROGRAM.format(root=str(root), scenario=SCENARIO, runs=runs)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=root)
    if done.returncode != 0:
        raise SystemExit(f"{root}: {done.stderr.strip().splitlines()[-1]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=256)
    parser.add_argument("--against", default=None, help="a commit to measure beside this tree")
    options = parser.parse_args()
    trees = [("now", ROOT)]
    with tempfile.TemporaryDirectory() as folder:
        if options.against:
            other = Path(folder) / "other"
            subprocess.run(["git", "worktree", "add", "--detach", str(other), options.against], cwd=ROOT,
                           check=True, capture_output=True)
            trees.insert(0, (options.against, other))
        try:
            results = {label: measure(root, options.runs) for label, root in trees}
        finally:
            if options.against:
                subprocess.run(["git", "worktree", "remove", "--force", str(other)], cwd=ROOT, capture_output=True)
    print(f"{options.runs} runs a chunk, {results['now']['full output']['rows']} rows a run with full output; "
          "per run [us], median (min) of 7; compile [s]")
    header = f"{'':8s} {'summary-only':>16s} {'full output':>16s} {'full/summary':>13s} {'compile s/f':>12s}"
    print(header)
    print("-" * len(header))
    for label, result in results.items():
        summary, full = result["summary-only"], result["full output"]
        print(f"{label:8s} {summary['median']:8.1f} ({summary['min']:5.1f}) {full['median']:8.1f} ({full['min']:5.0f})"
              f" {full['median'] / summary['median']:12.1f}x {summary['compile']:5.1f}/{full['compile']:4.1f}")


if __name__ == "__main__":
    main()

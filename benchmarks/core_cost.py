"""What the element core costs: the same measurements on this tree and on an earlier commit, in one run.

Measured in fresh processes (the on-disk compilation cache off), alternating
between the two trees, each measurement repeated ``--rounds`` times and the
median kept:

- compile: the first ``simulate`` of the canonical scene (exercise 6 direct
  start) less a warm one: tracing and compiling the restart loop (s);
- warm single run: ``simulate`` of the same scene once compiled, median of 30 (ms);
- sweep per run: ``sweep(..., summary_only=True)`` of 1 000 engagement forces on
  scenarios/force_sweep_engage_at_speed.yaml, once compiled, median of 7 (us per run);
- sweep compile: the first such sweep less a warm one (s).

    python benchmarks/core_cost.py                 # against the last commit before the element core
    python benchmarks/core_cost.py --before REF    # against any commit
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BEFORE = "980a267"  # the two-shaft core, before elements

MEASURE = r"""
import json, statistics, sys, time
sys.path.insert(0, sys.argv[1])
import hoistsim
assert hoistsim.__file__.startswith(sys.argv[1]), hoistsim.__file__
from hoistsim import load_scenario, simulate, sweep

def clock(func):
    start = time.perf_counter(); func(); return time.perf_counter() - start

one = load_scenario(sys.argv[1] + "/scenarios/exercise6_direct_start.yaml")
first = clock(lambda: simulate(one))
warm = [clock(lambda: simulate(one)) for _ in range(30)]
many = load_scenario(sys.argv[1] + "/scenarios/force_sweep_engage_at_speed.yaml",
                     sweeps=["clutch.engagement_force=3 kN:12 kN:1000"])
sweep_first = clock(lambda: sweep(many, summary_only=True))
sweeps = [clock(lambda: sweep(many, summary_only=True)) for _ in range(7)]
print(json.dumps({
    "compile_s": first - statistics.median(warm),
    "single_ms": 1e3 * statistics.median(warm),
    "sweep_us_per_run": 1e6 * statistics.median(sweeps) / 1000,
    "sweep_compile_s": sweep_first - statistics.median(sweeps),
}))
"""

ROWS = [("compile_s", "compile, canonical scene [s]", "{:.2f}"),
        ("single_ms", "warm single run [ms]", "{:.2f}"),
        ("sweep_us_per_run", "sweep, summary-only, per run [us]", "{:.0f}"),
        ("sweep_compile_s", "sweep compile (1024-run chunk) [s]", "{:.2f}")]


def measure(tree: Path) -> dict:
    env = dict(os.environ, HOISTSIM_CACHE_DIR="", PYTHONPATH=str(tree))
    out = subprocess.run([sys.executable, "-c", MEASURE, str(tree)], env=env, cwd=tree, check=True,
                         capture_output=True, text=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--before", default=BEFORE, help="the commit to compare with")
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        old = Path(folder) / "before"
        subprocess.run(["git", "worktree", "add", "--detach", str(old), args.before], cwd=ROOT, check=True,
                       capture_output=True)
        try:
            results = {"before": [], "after": []}
            for _ in range(args.rounds):
                results["before"].append(measure(old))
                results["after"].append(measure(ROOT))
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(old)], cwd=ROOT, capture_output=True)
    from hoistsim.results.report import table

    rows = []
    for key, label, form in ROWS:
        before = statistics.median(r[key] for r in results["before"])
        after = statistics.median(r[key] for r in results["after"])
        rows.append([label, form.format(before), form.format(after), f"{100 * (after / before - 1):+.0f} %"])
    print(f"before: {args.before}, after: this tree; medians of {args.rounds} rounds in fresh processes")
    print(table(["measure", "before", "after", "change"], rows))


if __name__ == "__main__":
    main()

"""What drawing a results file's figures costs: `plot_file` in a warm process, this tree beside another commit.

A scenario is run once (this tree) into a results file; then, for each tree in turn and `--rounds`
times over (interleaved: this machine's speed drifts by tens of percent over minutes), a fresh
process draws the file's figures once to warm matplotlib up and then `--draws` times more, and
prints the median.  Medians and spread of the rounds' medians per tree.  This is the figure's part
of save -> figure under `hoistsim watch` (benchmarks/watch_latency.py times the whole of it).

    python benchmarks/figure_cost.py [--scenario exercise6_direct_start.yaml] [--against 0b3a7a2]
                                     [--rounds 5] [--draws 7]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from trees import trees

ROOT = Path(__file__).resolve().parents[1]

# run in each tree: its own plot_file (hoistsim.plotting before the package had a folder per layer)
DRAW = """
import statistics, sys, time
import matplotlib
matplotlib.use("Agg")
try:
    from hoistsim.figures.files import plot_file
except ImportError:
    from hoistsim.plotting import plot_file
results, figure, draws = sys.argv[1], sys.argv[2], int(sys.argv[3])
plot_file(results, figure)
times = []
for _ in range(draws):
    started = time.perf_counter()
    plot_file(results, figure)
    times.append(time.perf_counter() - started)
print(statistics.median(times))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="exercise6_direct_start.yaml")
    parser.add_argument("--against", default=None, help="a commit to measure beside this tree")
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--draws", type=int, default=7)
    options = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        results = folder / "results.h5"
        env = dict(os.environ, HOISTSIM_CACHE_DIR=str(folder / "cache"), PYTHONPATH=str(ROOT))
        subprocess.run([sys.executable, "-m", "hoistsim.cli", "run", str(ROOT / "scenarios" / options.scenario),
                        "-o", str(results)], check=True, capture_output=True, env=env, cwd=ROOT)
        with trees(folder, options.against) as roots:
            medians = {label: [] for label in roots}
            for _ in range(options.rounds):
                for label, root in roots.items():
                    done = subprocess.run(
                        [sys.executable, "-c", DRAW, str(results), str(folder / f"{label}.png"), str(options.draws)],
                        check=True, capture_output=True, text=True, cwd=root, env=dict(env, PYTHONPATH=str(root)))
                    medians[label].append(float(done.stdout.split()[-1]))
    print(f"scenario: {options.scenario}; plot_file, median of {options.draws} draws a round, {options.rounds} rounds")
    print(f"{'tree':<10} {'median [s]':>11} {'min [s]':>9} {'max [s]':>9}")
    for label, values in medians.items():
        print(f"{label:<10} {statistics.median(values):>11.3f} {min(values):>9.3f} {max(values):>9.3f}")


if __name__ == "__main__":
    main()

"""Modelica's Rotational examples (scenarios/modelica/): each one's first run in a fresh process (its compile
included, the persistent compilation cache off) and its warm run, the median of a few in that process.

    python benchmarks/modelica_examples.py [--repeats 3]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PROGRAM = """
import sys, time, statistics
sys.path.insert(0, {root!r})
from hoistsim import load_scenario, simulate
scenario = load_scenario({path!r})
started = time.perf_counter(); run = simulate(scenario); first = time.perf_counter() - started
warm = []
for _ in range(5):
    started = time.perf_counter(); simulate(scenario); warm.append(time.perf_counter() - started)
print(first, statistics.median(warm), float(run.time[-1]))
"""


def measure(path: Path) -> tuple[float, float, float]:
    env = dict(os.environ, HOISTSIM_CACHE_DIR="")  # no stored programs: the first run compiles
    out = subprocess.run([sys.executable, "-c", PROGRAM.format(root=str(ROOT), path=str(path))], env=env,
                         capture_output=True, text=True, check=True).stdout.split()
    return tuple(float(v) for v in out[-3:])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    paths = sorted((ROOT / "scenarios" / "modelica").glob("*.yaml"))
    width = max(len("example"), *(len(path.stem) for path in paths))
    print(f"{'example':<{width}} {'first run [s]':>14} {'warm run [ms]':>14} {'simulated [s]':>14}")
    for path in paths:
        runs = [measure(path) for _ in range(args.repeats)]
        first = statistics.median(r[0] for r in runs)
        warm = statistics.median(r[1] for r in runs)
        print(f"{path.stem:<{width}} {first:>14.2f} {warm * 1e3:>14.1f} {runs[0][2]:>14.3g}")


if __name__ == "__main__":
    main()

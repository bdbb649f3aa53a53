"""Start-up cost of the command line: `hoistsim --help`, and the cold and warm wall time of `hoistsim run`.

Cold: an empty cache folder (everything is traced and compiled).  Warm: the
same command again, the compiled loop loaded from the cache; median of
`--repeats`.  Beside them, in the same minutes, `python -c "import jax"`: the
floor a command that computes anything stands on.  With `--against COMMIT`
the same commands are timed on that commit too (a git worktree), interleaved.
Also a warm run inside one Python process (`hoistsim.simulate`, compiled once
first): median and min of 20.

    python benchmarks/startup.py [--repeats 7] [--against c33d384] [--scenario exercise6_direct_start.yaml]
"""

from __future__ import annotations

import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from trees import trees

ROOT = Path(__file__).resolve().parents[1]


def wall(command, env, cwd) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, env=env, cwd=cwd)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--against", default=None, help="a commit to measure beside this tree")
    parser.add_argument("--scenario", default="exercise6_direct_start.yaml")
    options = parser.parse_args()
    scenario = str(ROOT / "scenarios" / options.scenario)
    with tempfile.TemporaryDirectory() as folder, trees(folder, options.against) as roots:
        folder = Path(folder)
        rows = {}
        jax = [wall([sys.executable, "-c", "import jax"], dict(os.environ), folder)
               for _ in range(options.repeats)]
        for label, root in roots.items():
            env = dict(os.environ, HOISTSIM_CACHE_DIR=str(folder / f"cache-{label}"), PYTHONPATH=str(root))
            run = [sys.executable, "-m", "hoistsim.cli", "run", scenario, "-o", str(folder / "out.h5")]
            cold = wall(run, env, root)
            rows[label] = {"cold": cold, "warm": [], "help": []}
        for _ in range(options.repeats):  # interleaved: both trees in the same minutes
            for label, root in roots.items():
                env = dict(os.environ, HOISTSIM_CACHE_DIR=str(folder / f"cache-{label}"), PYTHONPATH=str(root))
                run = [sys.executable, "-m", "hoistsim.cli", "run", scenario, "-o", str(folder / "out.h5")]
                rows[label]["warm"].append(wall(run, env, root))
                rows[label]["help"].append(wall([sys.executable, "-m", "hoistsim.cli", "--help"], env, root))
            jax.append(wall([sys.executable, "-c", "import jax"], dict(os.environ), folder))
    floor = statistics.median(jax)
    print(f"scenario: {Path(scenario).name}; python -c 'import jax': {floor:.2f} s (median of {len(jax)})")
    print(f"{'tree':<10} {'--help [s]':>10} {'cold run [s]':>13} {'warm run [s]':>13} {'warm / import jax':>18}")
    for label, row in rows.items():
        warm = statistics.median(row["warm"])
        print(f"{label:<10} {statistics.median(row['help']):>10.2f} {row['cold']:>13.2f} {warm:>13.2f} "
              f"{warm / floor:>17.2f}x")
    from hoistsim import load_scenario, simulate

    loaded = load_scenario(scenario)
    simulate(loaded)  # compile
    inside = []
    for _ in range(20):
        start = time.perf_counter()
        simulate(loaded)
        inside.append(time.perf_counter() - start)
    print(f"in-process simulate (warm, this tree): {statistics.median(inside) * 1e3:.2f} ms median, "
          f"{min(inside) * 1e3:.2f} ms min")


if __name__ == "__main__":
    main()

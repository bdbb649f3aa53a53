"""What `hoistsim plot OUT.h5 -o FIG.png` costs as a whole command, this tree beside another commit.

A scenario is run once (this tree) into a results file; then `--repeats` times over, interleaved (this
machine's speed drifts by tens of percent over minutes), each tree draws the file's figures as a fresh
process, and `python -c "import jax"` is timed beside them: what a command that loads JAX pays before
it does anything.  Also, per tree, the modules `hoistsim plot` loads before it draws: whether JAX and
the machine are among them.  Medians of the repeats.  Python keeps its modules' bytecode, as a user's
does (``trees.user_environment``).

    python benchmarks/plot_startup.py [--scenario exercise6_direct_start.yaml] [--against 2e86004] [--repeats 9]
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from startup import wall
from trees import trees, user_environment

ROOT = Path(__file__).resolve().parents[1]

# what the command imports before it draws, in each tree
LOADED = ("import sys, hoistsim.figures.files; "
          "print('jax' in sys.modules, any(m.startswith('hoistsim.machine') for m in sys.modules))")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scenario", default="exercise6_direct_start.yaml")
    parser.add_argument("--against", default=None, help="a commit to measure beside this tree")
    parser.add_argument("--repeats", type=int, default=9)
    options = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder, trees(folder, options.against) as roots:
        folder = Path(folder)
        results = folder / "results.h5"
        subprocess.run([sys.executable, "-m", "hoistsim.cli", "run", str(ROOT / "scenarios" / options.scenario),
                        "-o", str(results)], check=True, capture_output=True, cwd=ROOT,
                       env=user_environment(HOISTSIM_CACHE_DIR=str(folder / "cache"), PYTHONPATH=str(ROOT)))
        environments = {label: user_environment(PYTHONPATH=str(root)) for label, root in roots.items()}
        plot = {label: [sys.executable, "-m", "hoistsim.cli", "plot", str(results), "-o", str(folder / f"{label}.png")]
                for label in roots}
        loads = {}
        for label, root in roots.items():
            wall(plot[label], environments[label], root)  # bytecode written, matplotlib's font cache warm
            done = subprocess.run([sys.executable, "-c", LOADED], capture_output=True, text=True,
                                  env=environments[label], cwd=root, check=True)
            loads[label] = done.stdout.split()
        times = {label: [] for label in roots}
        jax = []
        for _ in range(options.repeats):
            for label, root in roots.items():
                times[label].append(wall(plot[label], environments[label], root))
            jax.append(wall([sys.executable, "-c", "import jax"], user_environment(), folder))
    floor = statistics.median(jax)
    print(f"scenario: {options.scenario}; python -c 'import jax': {floor:.2f} s (median of {len(jax)})")
    print(f"{'tree':<10} {'hoistsim plot [s]':>18} {'min [s]':>8} {'max [s]':>8} {'loads jax':>10} {'loads machine':>14}")
    for label in times:
        row = times[label]
        print(f"{label:<10} {statistics.median(row):>18.2f} {min(row):>8.2f} {max(row):>8.2f} "
              f"{loads[label][0]:>10} {loads[label][1]:>14}")


if __name__ == "__main__":
    main()

"""Start-up cost of the command line: `hoistsim --help`, and the cold and warm wall time of `hoistsim run`.

Cold: an empty cache folder (everything is traced and compiled).  Warm: the
same command again, the compiled loop loaded from the cache; median of
`--repeats`.  Beside them, in the same minutes, `python -c "import jax"`: the
floor a command that computes anything stands on.  With `--against COMMIT`
the same commands are timed on that commit too (a git worktree), interleaved.
Also a warm run inside one Python process (`hoistsim.simulate`, compiled once
first): median and min of 20; and its results file written (`write_runs`), the first write and the
median of 14 more.  And a bad edit: a copy of the scenario run once (so that its
command reads its program ahead), then given a misspelt key, timed from the command to its one-line
error.  Python keeps its modules' bytecode, as a user's does (``trees.user_environment``;
``KEEP_ENVIRONMENT=1`` measures with the environment as it is).

    python benchmarks/startup.py [--repeats 7] [--against c33d384] [--scenario exercise6_direct_start.yaml]
"""

from __future__ import annotations

import argparse
import re
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from trees import trees, user_environment

ROOT = Path(__file__).resolve().parents[1]


def wall(command, env, cwd, status: int = 0) -> float:
    start = time.perf_counter()
    done = subprocess.run(command, capture_output=True, env=env, cwd=cwd)
    taken = time.perf_counter() - start
    if done.returncode != status:
        raise SystemExit(f"{' '.join(map(str, command))}: exit {done.returncode}: {done.stderr.decode()[-400:]}")
    return taken


def _command(scenario: Path, folder: Path) -> list:
    return [sys.executable, "-m", "hoistsim.cli", "run", str(scenario), "-o", str(folder / "edited.h5")]


def _misspelt(text: str) -> str:
    """The scenario with its first key misspelt (a bad edit: one line naming the key, exit 2)."""
    key = re.search(r"^(\s*)(\w+):", text, re.MULTILINE)
    return text[:key.start(2)] + key.group(2) + "x" + text[key.end(2):]


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
        jax = [wall([sys.executable, "-c", "import jax"], user_environment(), folder)
               for _ in range(options.repeats)]
        for label, root in roots.items():
            env = user_environment(HOISTSIM_CACHE_DIR=str(folder / f"cache-{label}"), PYTHONPATH=str(root))
            run = [sys.executable, "-m", "hoistsim.cli", "run", scenario, "-o", str(folder / "out.h5")]
            cold = wall(run, env, root)
            rows[label] = {"cold": cold, "warm": [], "help": [], "bad": []}
            # a copy of the scenario run once (its command remembered), then given a misspelt key: a bad edit
            edited = folder / f"edited-{label}.yaml"
            edited.write_text(Path(scenario).read_text(encoding="utf-8"), encoding="utf-8")
            wall(_command(edited, folder), env, root)
            edited.write_text(_misspelt(edited.read_text(encoding="utf-8")), encoding="utf-8")
        for _ in range(options.repeats):  # interleaved: both trees in the same minutes
            for label, root in roots.items():
                env = user_environment(HOISTSIM_CACHE_DIR=str(folder / f"cache-{label}"), PYTHONPATH=str(root))
                run = [sys.executable, "-m", "hoistsim.cli", "run", scenario, "-o", str(folder / "out.h5")]
                rows[label]["warm"].append(wall(run, env, root))
                rows[label]["help"].append(wall([sys.executable, "-m", "hoistsim.cli", "--help"], env, root))
                rows[label]["bad"].append(wall(_command(folder / f"edited-{label}.yaml", folder), env, root, status=2))
            jax.append(wall([sys.executable, "-c", "import jax"], user_environment(), folder))
    floor = statistics.median(jax)
    print(f"scenario: {Path(scenario).name}; python -c 'import jax': {floor:.2f} s (median of {len(jax)})")
    print(f"{'tree':<10} {'--help [s]':>10} {'cold run [s]':>13} {'warm run [s]':>13} {'warm / import jax':>18} "
          f"{'bad edit [s]':>13}")
    for label, row in rows.items():
        warm = statistics.median(row["warm"])
        print(f"{label:<10} {statistics.median(row['help']):>10.2f} {row['cold']:>13.2f} {warm:>13.2f} "
              f"{warm / floor:>17.2f}x {statistics.median(row['bad']):>13.2f}")
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
    from hoistsim.results.output import write_runs

    run = simulate(loaded)
    writes = []
    with tempfile.TemporaryDirectory() as folder:
        for _ in range(15):  # the first in a process apart: it starts HDF5
            start = time.perf_counter()
            write_runs(Path(folder) / "run.h5", [run], command="startup.py")
            writes.append(time.perf_counter() - start)
    print(f"in-process write_runs (this tree): {writes[0] * 1e3:.0f} ms the first, "
          f"{statistics.median(writes[1:]) * 1e3:.0f} ms median of the next {len(writes) - 1}")


if __name__ == "__main__":
    main()

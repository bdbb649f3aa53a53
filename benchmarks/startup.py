"""Start-up cost of the command line: cold and warm wall time of `hoistsim run`.

Cold: an empty cache folder (everything is traced and compiled).  Warm: the
same command again, the compiled loop loaded from the cache; median of 5.
Also a warm run inside one Python process (`hoistsim.simulate`, compiled once
first): median and min of 20.

    python benchmarks/startup.py [SCENARIO]
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def wall(command, env) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, capture_output=True, env=env, cwd=ROOT)
    return time.perf_counter() - start


def main() -> None:
    scenario = sys.argv[1] if len(sys.argv) > 1 else str(ROOT / "scenarios" / "exercise6_direct_start.yaml")
    with tempfile.TemporaryDirectory() as folder:
        env = dict(os.environ, HOISTSIM_CACHE_DIR=str(Path(folder) / "cache"))
        command = [sys.executable, "-m", "hoistsim.cli", "run", scenario, "-o", str(Path(folder) / "out.h5")]
        cold = wall(command, env)
        warm = [wall(command, env) for _ in range(5)]
        off = [wall(command, dict(env, HOISTSIM_CACHE_DIR="")) for _ in range(3)]
        bare = [wall([sys.executable, "-c", "import hoistsim.cli"], env) for _ in range(3)]
    print(f"scenario: {Path(scenario).name}")
    print(f"cold run (empty cache):        {cold:.2f} s")
    print(f"warm run (median of 5):        {statistics.median(warm):.2f} s  (min {min(warm):.2f} s)")
    print(f"cache turned off (median of 3): {statistics.median(off):.2f} s")
    print(f"of which importing the CLI:     {statistics.median(bare):.2f} s")
    from hoistsim import load_scenario, simulate

    loaded = load_scenario(scenario)
    simulate(loaded)  # compile
    inside = []
    for _ in range(20):
        start = time.perf_counter()
        simulate(loaded)
        inside.append(time.perf_counter() - start)
    print(f"in-process simulate (warm):     {statistics.median(inside) * 1e3:.2f} ms median, "
          f"{min(inside) * 1e3:.2f} ms min")


if __name__ == "__main__":
    main()

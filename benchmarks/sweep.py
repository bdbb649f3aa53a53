"""What a sweep costs, through the command line, against a scipy event-restart loop measured in the same run.

Scene: scenarios/engage_at_speed_with_brake.yaml (the motor runs up with the drum
held, the clutch force is ramped on over 0.5-0.6 s and the brake released at
0.6 s; 500 kg load, 3 s, rtol 1e-8, atol 1e-10), with a sweep that *lists* its
engagement-force tables in the file: [[0 s, 0 N], [0.5 s, 0 N], [0.6 s, F]], F
evenly spaced over 3-12 kN.  Both sides run the same hybrid model at the same
tolerances.

1. Marginal cost per scenario: `hoistsim run FILE -o OUT.h5 [--summary-only]` on
   files listing N1 and N2 tables, each a fresh process (persistent compilation
   cache warm), median of REPEATS; (T(N2) - T(N1)) / (N2 - N1) leaves out the
   process start, imports and loading the compiled program.  Summary-only, and
   full time series on a 2-row output grid (output_interval = duration: the
   rows are the start, the end and every event instant).
   The peer: hoistsim.references.scipy_reference.solve_scenario_with_scipy (a Python loop of
   solve_ivp RK45 with terminal events and restarts at every switch and table
   knot, no dense output), on SCIPY_SAMPLE evenly spaced scenarios of the
   same files; its cost per scenario is their mean.  The lock-up times of the
   two are compared run by run on that sample.
2. Scale: `--sweep "clutch.engagement_force=3 kN:12 kN:N"` summary-only on
   scenarios/force_sweep_engage_at_speed.yaml from 1e3 to 1e6 runs: wall time,
   cost per run and the process's peak memory (each a fresh process).
3. A local Dask cluster (`--workers 1` and `--workers 2`) on a 1e5 sweep: wall
   time of the command, and of the sweep alone once the workers are up and
   compiled (hoistsim.sweep(..., scheduler=...) on a running LocalCluster).
4. Lanes that wait: the same 8 192 forces listed in random order, run as
   given and ordered within each block by the swept value (the default).

    python benchmarks/sweep.py              # every part (about 12 min on 2 cores)
    python benchmarks/sweep.py --quick      # part 1 with small files, part 2 to 1e4
"""

from __future__ import annotations

import argparse
import json
import math
import random
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from hoistsim import load_scenario
from hoistsim.references.scipy_reference import solve_scenario_with_scipy
from hoistsim.results.report import table
from hoistsim.running import blocks
from hoistsim.scenario.sweep_runs import sweep_values

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "scenarios" / "engage_at_speed_with_brake.yaml"
RANGE_SCENARIO = ROOT / "scenarios" / "force_sweep_engage_at_speed.yaml"
SCIPY_SAMPLE = 100
REPEATS = 3

# Runs a command and prints its wall time and peak memory (the child's own): a fresh process each time.
_MEASURE = """
import resource, subprocess, sys, time, json
start = time.perf_counter()
done = subprocess.run(sys.argv[1:], capture_output=True, text=True)
wall = time.perf_counter() - start
if done.returncode:
    sys.exit(done.stderr)
print(json.dumps({"wall": wall, "rss_mib": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1024}))
"""


def measured(args: list[str]) -> dict:
    out = subprocess.run([sys.executable, "-c", _MEASURE, *args], capture_output=True, text=True)
    if out.returncode:
        raise SystemExit(f"{' '.join(args)} failed:\n{out.stderr}")
    return json.loads(out.stdout)


def hoistsim_cli(*args: str) -> list[str]:
    return [str(Path(sys.executable).with_name("hoistsim")), *args]


def listed_file(folder: Path, count: int, *, two_rows: bool = False, shuffled: bool = False,
                forces: bool = False) -> Path:
    """The scene with a sweep listing ``count`` values: force tables (or plain forces, ``forces``)."""
    values = np.linspace(3000.0, 12000.0, count)
    if shuffled:
        values = values[random.Random(1).sample(range(count), count)]
    text = BASE.read_text()
    if two_rows:
        text = text.replace("output_interval: 1 ms", "output_interval: 3 s")
    if forces:
        items = "".join(f"\n    - {f:.3f} N" for f in values)
    else:
        items = "".join(f"\n    - [[0 s, 0 N], [0.5 s, 0 N], [0.6 s, {f:.3f} N]]" for f in values)
    path = folder / f"listed_{count}{'_2rows' if two_rows else ''}{'_shuffled' if shuffled else ''}.yaml"
    path.write_text(text + "sweep:\n  clutch.engagement_force:" + items + "\n")
    return path


def cli_seconds(args: list[str], repeats: int = REPEATS) -> float:
    return statistics.median(measured(hoistsim_cli(*args))["wall"] for _ in range(repeats))


def peer(path: Path, sample: int) -> tuple[float, dict]:
    """scipy's mean seconds per scenario over an evenly spaced sample, and its lock-up times by run."""
    pairs = sweep_values(load_scenario(path))
    picks = np.unique(np.linspace(0, len(pairs) - 1, min(sample, len(pairs))).round().astype(int))
    locks, spent = {}, 0.0
    for i in picks:
        start = time.perf_counter()
        events, _, _, _ = solve_scenario_with_scipy(pairs[i][1], method="RK45")
        spent += time.perf_counter() - start
        first = [t for t, kind in events if kind == "lock"]
        locks[int(i)] = first[0] if first else math.nan
    return spent / len(picks), locks


def lockup_difference(path: Path, locks: dict) -> float:
    import h5py

    with h5py.File(path, "r") as f:
        ours = f["runs/lockup_time"][()]
    worst = 0.0
    for i, theirs in locks.items():
        if math.isnan(theirs) or math.isnan(ours[i]):
            assert math.isnan(theirs) and math.isnan(ours[i]), (i, theirs, ours[i])
            continue
        worst = max(worst, abs(ours[i] - theirs))
    return worst


def marginal(folder: Path, small: int, large: int) -> list[list[str]]:
    rows = []
    per_peer, locks = peer(listed_file(folder, large), SCIPY_SAMPLE)
    for name, two_rows, options in (("summary-only", False, ["--summary-only"]),
                                    ("full output, 2-row grid", True, [])):
        files = [listed_file(folder, n, two_rows=two_rows) for n in (small, large)]
        out = folder / "out.h5"
        subprocess.run(hoistsim_cli("run", str(files[0]), "-o", str(out), *options), capture_output=True)  # compile
        seconds = [cli_seconds(["run", str(f), "-o", str(out), *options]) for f in files]
        cost = (seconds[1] - seconds[0]) / (large - small)
        rows.append([name, f"{seconds[0]:.2f}", f"{seconds[1]:.2f}", f"{cost * 1e6:.0f}", f"{per_peer * 1e6:.0f}",
                     f"{per_peer / cost:.0f}x", f"{lockup_difference(out, locks):.1e}"])
    return rows


def scale(counts) -> list[list[str]]:
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        out = str(Path(folder) / "scale.h5")
        sweep = lambda n: hoistsim_cli("run", str(RANGE_SCENARIO), "-o", out, "--summary-only",  # noqa: E731
                                       "--sweep", f"clutch.engagement_force=3 kN:12 kN:{n}")
        # compiled once for every chunk width the counts will use (stored: each timed process loads it)
        scenario = load_scenario(RANGE_SCENARIO)
        for width in sorted({blocks.chunk_for(scenario, True, n) for n in counts}):
            subprocess.run(sweep(width), capture_output=True)
        for n in counts:
            m = measured(sweep(n))
            rows.append([f"{n:.0e}", f"{m['wall']:.1f}", f"{m['wall'] / n * 1e6:.0f}", f"{m['rss_mib']:.0f}"])
            print(f"  scale {n:.0e}: {m['wall']:.1f} s", flush=True)
    return rows


def cluster(count: int) -> list[list[str]]:
    from distributed import LocalCluster

    import hoistsim

    rows = []
    scenario = load_scenario(RANGE_SCENARIO, sweeps=[f"clutch.engagement_force=3 kN:12 kN:{count}"])
    small = load_scenario(RANGE_SCENARIO, sweeps=["clutch.engagement_force=3 kN:12 kN:4096"])
    with tempfile.TemporaryDirectory() as folder:
        out = Path(folder) / "cluster.h5"
        alone = measured(hoistsim_cli("run", str(RANGE_SCENARIO), "-o", str(out), "--summary-only",
                                      "--sweep", f"clutch.engagement_force=3 kN:12 kN:{count}"))["wall"]
        hoistsim.sweep(small, summary_only=True)  # compiled (or loaded) here too
        start = time.perf_counter()
        hoistsim.sweep(scenario, summary_only=True, output=out)
        in_process = time.perf_counter() - start
        rows.append(["no cluster (this process)", f"{alone:.1f}", f"{in_process:.1f}", "-"])
        base = None
        for workers in (1, 2):
            wall = measured(hoistsim_cli("run", str(RANGE_SCENARIO), "-o", str(out), "--summary-only",
                                         "--workers", str(workers),
                                         "--sweep", f"clutch.engagement_force=3 kN:12 kN:{count}"))["wall"]
            with LocalCluster(n_workers=workers, threads_per_worker=1, host="127.0.0.1",
                              dashboard_address=":0") as running:
                hoistsim.sweep(small, summary_only=True, scheduler=running.scheduler_address)  # workers compile
                start = time.perf_counter()
                hoistsim.sweep(scenario, summary_only=True, output=out, scheduler=running.scheduler_address)
                swept = time.perf_counter() - start
            base = base or swept
            rows.append([f"--workers {workers}", f"{wall:.1f}", f"{swept:.1f}", f"{base / swept:.2f}x"])
            print(f"  {workers} worker(s): {wall:.1f} s, sweep {swept:.1f} s", flush=True)
    return rows


def lanes(folder: Path, count: int) -> list[list[str]]:
    import hoistsim

    listed = load_scenario(listed_file(folder, count, shuffled=True, forces=True))
    hoistsim.sweep(listed, summary_only=True)  # compile
    rows = []
    for name, ordered in (("as listed (random order)", False), ("ordered by the swept value", True)):
        blocks.ORDER_BY_SWEPT_VALUE = ordered
        seconds = statistics.median(_timed(lambda: hoistsim.sweep(listed, summary_only=True)) for _ in range(3))
        rows.append([name, f"{seconds:.2f}", f"{seconds / count * 1e6:.0f}"])
    blocks.ORDER_BY_SWEPT_VALUE = True
    return rows


def _timed(func) -> float:
    start = time.perf_counter()
    func()
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small files, scale to 1e4, no cluster")
    parser.add_argument("--part", type=int, choices=(1, 2, 3, 4), help="only this part")
    args = parser.parse_args()
    from hoistsim import _jax

    _jax.enable_compilation_cache()  # as the command line does: a program compiled once is loaded after
    with tempfile.TemporaryDirectory() as folder:
        folder = Path(folder)
        wanted = lambda part: args.part in (None, part)  # noqa: E731
        if wanted(1):
            small, large = (200, 1000) if args.quick else (1000, 5000)
            print(f"1. marginal cost per scenario, files listing {small} and {large} force tables", flush=True)
            rows = marginal(folder, small, large)
            print(table(["output", f"{small} runs [s]", f"{large} runs [s]", "hoistsim per run [us]",
                         "scipy per run [us]", "ratio", "lock-up diff [s]"], rows))
            print(f"(scipy: mean of {SCIPY_SAMPLE} evenly spaced scenarios of the {large}-table file; "
                  "hoistsim: (T(large) - T(small)) / (large - small), medians of "
                  f"{REPEATS} fresh processes)\n", flush=True)
        if wanted(2):
            counts = [1000, 10000] if args.quick else [1000, 10000, 100000, 1000000]
            print("2. summary-only sweeps through the command line, --sweep FROM:TO:COUNT", flush=True)
            print(table(["runs", "wall [s]", "per run [us]", "peak RSS [MiB]"], scale(counts)) + "\n", flush=True)
        if wanted(3) and not args.quick:
            print("3. a local Dask cluster, 1e5 runs summary-only", flush=True)
            print(table(["cluster", "command wall [s]", "sweep, workers up [s]", "speed-up"], cluster(100000))
                  + "\n", flush=True)
        if wanted(4):
            print("4. lanes that wait: 8192 forces listed in random order", flush=True)
            print(table(["order", "sweep [s]", "per run [us]"], lanes(folder, 8192)))


if __name__ == "__main__":
    main()

"""What a run costs hoistsim against a hand-compiled peer (Numba, one core), with lock-up times compared run by run.

Two scenes of the exercise-6 hoist (500 kg, rtol 1e-8, atol 1e-10), each a sweep of N engagement forces:

1. "stepped": scenarios/engage_at_speed_with_brake.yaml with the force table
   [[0 s, 0 N], [0.35 s, 0 N], [0.35 s, F]] and the brake released at 0.35 s, 2 s; the file lists
   the N tables (F evenly spaced over 3.8-12 kN), as benchmarks/sweep.py's listed_file does.
2. "direct start": scenarios/exercise6_direct_start.yaml swept over
   clutch.engagement_force=2 kN:6 kN:N (3 s).

For each scene, in this one process:

- compiled first: hoistsim (a small sweep of the same chunk width, then one untimed call of the full
  sweep; compile: the small sweep's first call less a warm one) and the Numba peer
  (benchmarks/numba_peer.py: DP5, event location on the dense output, restarts; one core, the same
  forces; compile: its first call of two runs less a warm one).
- then 5 rounds, each: hoistsim warm, ``hoistsim.sweep(scenario, summary_only=True)`` as a user runs
  it (each block's host work overlapping the last block's compiled calls; each chunk split over the
  process's CPU devices, one per core); the peer on one core, then on every core (prange); hoistsim again
  with every compiled call waited for (hoistsim._jax.executable wrapped, each call
  jax.block_until_ready): the compiled calls alone ("engine alone") and the rest ("host alone":
  building the runs, their plans, reading summaries back).  Medians of the 5.  The calls are
  interleaved because this machine's speed drifts by tens of percent over minutes.
- agreement: lock-up times run by run (largest |difference| where both lock; runs where one locks
  and the other doesn't), lock counts, final speeds and slip energy (largest relative difference).

Results are printed and written to benchmarks/results/engine_cost.csv (with ``--one-core``, the whole
process pinned to one core, XLA's threads too: engine_cost_one_core.csv).

    python benchmarks/engine_cost.py              # N = 4000 runs a scene
    python benchmarks/engine_cost.py --runs 1000
    python benchmarks/engine_cost.py --quick      # N = 200
"""

from __future__ import annotations

import argparse
import csv
import math
import os
import statistics
import sys
import tempfile
import time
from pathlib import Path

if "--one-core" in sys.argv:  # before XLA starts its threads: every thread of this process on one core
    os.sched_setaffinity(0, {min(os.sched_getaffinity(0))})

import jax  # noqa: E402
import numba_peer  # noqa: E402
import numpy as np  # noqa: E402

import hoistsim  # noqa: E402
import hoistsim._jax  # noqa: E402
from hoistsim import load_scenario  # noqa: E402
from hoistsim.results.report import table  # noqa: E402
from hoistsim.running.blocks import chunk_for  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
STEPPED = ROOT / "scenarios" / "engage_at_speed_with_brake.yaml"
DIRECT = ROOT / "scenarios" / "exercise6_direct_start.yaml"
RESULTS = ROOT / "benchmarks" / "results" / "engine_cost.csv"
REPEATS = 5
SMALL = 64  # runs of the compiling sweep


def stepped_file(folder: Path, forces: np.ndarray, name: str) -> Path:
    """Scene 1 with a sweep listing a force table for each of ``forces``."""
    text = STEPPED.read_text()
    for old, new in (("release_time: 0.6 s", "release_time: 0.35 s"), ("duration: 3 s", "duration: 2 s"),
                     ("engagement_force: [[0 s, 0 N], [0.5 s, 0 N], [0.6 s, 5000 N]]",
                      "engagement_force: [[0 s, 0 N], [0.35 s, 0 N], [0.35 s, 5000 N]]")):
        assert old in text, f"{STEPPED.name} no longer has {old!r}"
        text = text.replace(old, new)
    items = "".join(f"\n    - [[0 s, 0 N], [0.35 s, 0 N], [0.35 s, {float(f)!r} N]]" for f in forces)
    path = folder / f"{name}.yaml"
    path.write_text(text + "sweep:\n  clutch.engagement_force:" + items + "\n")
    return path


def machine_of(scenario) -> numba_peer.Machine:
    """The peer's machine from the scenario's own (SI) numbers, so both run the same constants."""
    clutch, gears = scenario.clutch, scenario.gears
    assert clutch.mean_radius == "uniform_wear"
    assert clutch.driving_inertia == clutch.driven_inertia == gears.pinion_inertia == gears.wheel_inertia == 0
    return numba_peer.exercise6_machine(
        motor_inertia=scenario.motor.moment_of_inertia, load_mass=scenario.load.mass,
        drum_inertia=scenario.drum.inertia, drum_diameter=scenario.drum.diameter,
        pinion_teeth=gears.pinion_teeth, wheel_teeth=gears.wheel_teeth,
        stall_torque=scenario.motor.stall_torque, no_load_rpm=scenario.motor.no_load_speed * 60 / (2 * math.pi),
        inner_radius=clutch.inner_radius, outer_radius=clutch.outer_radius,
        half_angle_deg=math.degrees(clutch.half_angle), surfaces=clutch.surfaces,
        static_friction=clutch.static_friction, kinetic_friction=clutch.kinetic_friction, gravity=scenario.gravity)


class EngineClock:
    """While active, every compiled program hoistsim runs is timed (waited for with block_until_ready)."""

    def __init__(self):
        self.seconds, self.widths = 0.0, set()

    def __enter__(self):
        self.original = hoistsim._jax.executable

        def timed_executable(jitted, *args, **how):
            run = self.original(jitted, *args, **how)

            def timed(*call_args):
                started = time.perf_counter()
                out = jax.block_until_ready(run(*call_args))
                self.seconds += time.perf_counter() - started
                self.widths.add(jax.tree.leaves(call_args)[0].shape[:1])
                return out
            return timed

        hoistsim._jax.executable = timed_executable
        return self

    def __exit__(self, *exc):
        hoistsim._jax.executable = self.original


def clock(func) -> tuple[float, object]:
    started = time.perf_counter()
    out = func()
    return time.perf_counter() - started, out


def cpu_clock(func) -> tuple[float, float, object]:
    """(wall seconds, CPU seconds of every thread of the process, result)."""
    started, cpu = time.perf_counter(), time.process_time()
    out = func()
    return time.perf_counter() - started, time.process_time() - cpu, out


def measure(full, small, runs: int, forces, scene) -> tuple[dict, dict]:
    """hoistsim and the peer on one scene, their timed calls interleaved (this machine's speed drifts by
    tens of percent over minutes: each ratio is of calls made side by side)."""
    chunk = chunk_for(full, True, runs)  # the full sweep's width: the small sweep compiles its program
    first, _ = clock(lambda: hoistsim.sweep(small, summary_only=True, chunk_size=chunk))
    warm, _ = clock(lambda: hoistsim.sweep(small, summary_only=True, chunk_size=chunk))
    result = hoistsim.sweep(full, summary_only=True)  # untimed: anything the small sweep did not compile
    if forces is None:  # the swept values as hoistsim made them
        forces = np.asarray(result.parameters["clutch.engagement_force"], float)
    machine = machine_of(full)
    peer_first, _ = clock(lambda: numba_peer.sweep(forces[:2], machine, scene))
    peer_warm, _ = clock(lambda: numba_peer.sweep(forces[:2], machine, scene))
    numba_peer.sweep(forces, machine, scene)
    numba_peer.sweep(forces[:2], machine, scene, parallel=True)  # compiled
    walls, cpus, peer_walls, parallel_walls, engines, serial = [], [], [], [], [], []
    for _ in range(REPEATS):  # as a user runs it: a block's host work overlaps the last block's compiled calls
        wall, cpu, result = cpu_clock(lambda: hoistsim.sweep(full, summary_only=True))
        walls.append(wall)
        cpus.append(cpu)
        wall, peer_result = clock(lambda: numba_peer.sweep(forces, machine, scene))
        peer_walls.append(wall)
        wall, _ = clock(lambda: numba_peer.sweep(forces, machine, scene, parallel=True))
        parallel_walls.append(wall)
        with EngineClock() as engine:  # every compiled call waited for: the engine alone, and the host's work
            wall, _ = clock(lambda: hoistsim.sweep(full, summary_only=True))
        engines.append(engine.seconds)
        serial.append(wall - engine.seconds)
    if engine.widths != {(chunk,)}:
        print(f"  note: hoistsim ran chunks {sorted(engine.widths)}, the compiling sweep {chunk}")
    if not engine.seconds:  # the engine no longer runs through _jax.executable: no engine-only time
        print("  note: no call went through hoistsim._jax.executable; engine time not measured")
        engines = [math.nan]
    ours = {"us": statistics.median(walls) / runs * 1e6, "cpu_us": statistics.median(cpus) / runs * 1e6,
            "engine_us": statistics.median(engines) / runs * 1e6,
            "host_us": statistics.median(serial) / runs * 1e6, "compile_s": first - warm, "result": result}
    peer = {"us": statistics.median(peer_walls) / len(forces) * 1e6, "compile_s": peer_first - peer_warm,
            "all_cores_us": statistics.median(parallel_walls) / len(forces) * 1e6,
            "result": peer_result}
    return ours, peer


def agreement(ours: dict, peer: dict) -> dict:
    a, b = np.asarray(ours["lockup_time"], float), peer["lockup_time"]
    both = ~np.isnan(a) & ~np.isnan(b)

    def relative(key):
        x, y = np.asarray(ours[key], float), peer[key]
        return float(np.max(np.abs(x - y) / np.maximum(np.abs(y), 1.0)))  # relative, absolute below 1
    return {"lockup_diff_s": float(np.max(np.abs(a - b)[both], initial=0.0)),
            "lock_mismatch": int(np.sum(np.isnan(a) != np.isnan(b))),
            "never_lock": int(np.sum(np.isnan(a) & np.isnan(b))),
            "count_mismatch": int(np.sum(np.asarray(ours["lock_events"]) != peer["lock_events"])),
            "speed_rel": max(relative("final_motor_speed"), relative("final_drum_speed")),
            "energy_rel": relative("slip_energy"), "steps": float(np.mean(peer["steps"]))}


def scenes(folder: Path, runs: int) -> list:
    """(name, full scenario, small scenario, forces (None: hoistsim's swept values), peer scene) a scene."""
    forces = np.round(np.linspace(3800.0, 12000.0, runs), 3)
    stepped = load_scenario(stepped_file(folder, forces, f"stepped_{runs}"))
    stepped_small = load_scenario(stepped_file(folder, forces[np.linspace(0, runs - 1, SMALL).astype(int)],
                                               "stepped_small"))
    direct = load_scenario(DIRECT, sweeps=[f"clutch.engagement_force=2 kN:6 kN:{runs}"])
    direct_small = load_scenario(DIRECT, sweeps=[f"clutch.engagement_force=2 kN:6 kN:{SMALL}"])
    return [("stepped", stepped, stepped_small, forces, numba_peer.stepped()),
            ("direct start", direct, direct_small, None, numba_peer.direct_start())]  # forces: as swept


def measure_full_output(folder: Path, runs: int) -> dict:
    """The stepped scene with every time series on its 1 ms grid (2 001 rows), kept in memory: per run."""
    forces = np.round(np.linspace(3800.0, 12000.0, runs), 3)
    scenario = load_scenario(stepped_file(folder, forces, f"stepped_full_{runs}"))
    hoistsim.sweep(scenario)  # compiled (and the chunk shape) first
    walls = [clock(lambda: hoistsim.sweep(scenario))[0] for _ in range(REPEATS)]
    return {"runs": runs, "us": statistics.median(walls) / runs * 1e6}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=4000)
    parser.add_argument("--quick", action="store_true", help="200 runs a scene")
    parser.add_argument("--full-runs", type=int, default=256, help="runs of the full-output measurement")
    parser.add_argument("--one-core", action="store_true",
                        help="the whole process on one core (hoistsim's XLA threads too); results to engine_cost_one_core.csv")
    options = parser.parse_args()
    runs = 200 if options.quick else options.runs
    cores = len(os.sched_getaffinity(0))
    results = RESULTS.with_name("engine_cost_one_core.csv") if options.one_core else RESULTS
    cost_rows, check_rows, records = [], [], []
    with tempfile.TemporaryDirectory() as folder:
        for name, full, small, forces, scene in scenes(Path(folder), runs):
            print(f"{name}: {runs} runs ...", flush=True)
            ours, peer = measure(full, small, runs, forces, scene)
            agree = agreement(ours["result"].summary, peer["result"])
            record = {"scene": name, "runs": runs, "cores": cores, "hoistsim_devices": len(jax.devices()),
                      "hoistsim_us_per_run": ours["us"],
                      "hoistsim_cpu_us_per_run": ours["cpu_us"],
                      "hoistsim_engine_us_per_run": ours["engine_us"],
                      "hoistsim_host_us_per_run": ours["host_us"], "numba_us_per_run": peer["us"],
                      "numba_all_cores_us_per_run": peer["all_cores_us"],
                      "hoistsim_compile_s": ours["compile_s"], "numba_compile_s": peer["compile_s"],
                      "numba_steps_per_run": agree["steps"], "lockup_max_abs_diff_s": agree["lockup_diff_s"],
                      "lockup_mismatched_runs": agree["lock_mismatch"], "runs_never_locking": agree["never_lock"],
                      "lock_count_mismatched_runs": agree["count_mismatch"],
                      "final_speed_max_rel_diff": agree["speed_rel"], "slip_energy_max_rel_diff": agree["energy_rel"]}
            records.append(record)
            cost_rows.append([name, f"{runs}", f"{ours['us']:.1f}", f"{ours['cpu_us']:.1f}", f"{ours['engine_us']:.1f}",
                              f"{ours['host_us']:.1f}", f"{peer['us']:.1f}", f"{peer['all_cores_us']:.1f}",
                              f"{ours['us'] / peer['us']:.2f}x", f"{ours['us'] / peer['all_cores_us']:.2f}x"])
            numba_compile = f"{peer['compile_s']:.2f}" if peer["compile_s"] > 0.05 else "0 (compiled above)"
            check_rows.append([name, f"{ours['compile_s']:.2f}", numba_compile, f"{agree['steps']:.0f}",
                               f"{agree['lockup_diff_s']:.1e}", f"{agree['lock_mismatch']}",
                               f"{agree['never_lock']}", f"{agree['count_mismatch']}",
                               f"{agree['speed_rel']:.1e}", f"{agree['energy_rel']:.1e}"])
        print("stepped, full output ...", flush=True)
        full_output = measure_full_output(Path(folder), 64 if options.quick else options.full_runs)
        records.append({"scene": "stepped, full output (1 ms grid)", "runs": full_output["runs"],
                        "hoistsim_us_per_run": full_output["us"]})
    print(f"\nper run, summary-only, in process on {cores} core(s), medians of {REPEATS} after compiling "
          f"(hoistsim vmapped, each chunk split over {len(jax.devices())} CPU device(s); Numba one core, a plain "
          f"loop, and all cores, prange)")
    print(table(["scene", "runs", "hoistsim [us]", "hoistsim CPU [us]", "engine alone [us]", "host alone [us]",
                 "numba 1 core [us]", f"numba {cores} cores [us]", "hoistsim/numba 1 core",
                 f"hoistsim/numba {cores} cores"], cost_rows))
    print()
    print(table(["scene", "hoistsim compile [s]", "numba compile [s]", "numba steps", "lock-up diff [s]",
                 "lock mismatch", "never lock", "lock count mismatch", "final speed rel", "slip energy rel"],
                check_rows))
    print(f"\nfull output (every series on the 1 ms grid, 2 001 rows, kept in memory), stepped scene, "
          f"{full_output['runs']} runs: {full_output['us']:.0f} us per run")
    results.parent.mkdir(exist_ok=True)
    with open(results, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(records[0]), restval="")
        writer.writeheader()
        writer.writerows(records)
    print(f"\nwritten {results.relative_to(ROOT)}")


if __name__ == "__main__":
    main()

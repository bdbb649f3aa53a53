"""What a new scene costs before its first result: the compile of one run, scene by scene.

Each measurement is a fresh Python process with the persistent compilation cache off: the first
`simulate` of the scene less a second (warm) one, the median of `--repeats` processes.  With
`--against COMMIT` the same scenes are measured on that commit too (a git worktree), interleaved, so
the two columns come from the same machine in the same minutes.

    python benchmarks/compile_time.py [--repeats 3] [--against 0ab3715]
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
EVERY_ELEMENT = ["brake.static_torque=3000 N*m", "brake.kinetic_torque=2000 N*m", "gears.efficiency=0.95",
                 "gears.backdrive_efficiency=0.9"]
SCENES = {  # name -> (scenario, overrides, a pawl too)
    "exercise 6, direct start": ("exercise6_direct_start.yaml", [], False),
    "every friction element of the hoist": ("engage_at_speed_with_brake.yaml", EVERY_ELEMENT, True),
    "CoupledClutches (4 shafts, 3 clutches)": ("coupled_clutches.yaml", [], False),
    "two-speed hoist (5 shafts, 2 clutches)": ("two_speed_hoist.yaml", [], False),
}
PROGRAM = """
import sys, time
sys.path.insert(0, {root!r})
from hoistsim import load_scenario, simulate
scenario = load_scenario({path!r}, overrides={overrides!r})
if {pawl!r}:
    from hoistsim.scenario.schema import RatchetSpec
    scenario = scenario.model_copy(update={{"ratchet": RatchetSpec()}})
started = time.perf_counter(); simulate(scenario); first = time.perf_counter() - started
started = time.perf_counter(); simulate(scenario); warm = time.perf_counter() - started
print(first - warm)
"""


def compile_seconds(root: Path, scene: tuple) -> float:
    name, overrides, pawl = scene
    path = ROOT / "scenarios" / name  # the scenarios of this tree, on either commit's code
    program = PROGRAM.format(root=str(root), path=str(path), overrides=overrides, pawl=pawl)
    env = dict(os.environ, HOISTSIM_CACHE_DIR="")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, env=env, cwd=root)
    if done.returncode != 0:
        return float("nan")  # the scene does not exist on that commit
    return float(done.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--against", default=None, help="a commit to measure beside this tree")
    options = parser.parse_args()
    with tempfile.TemporaryDirectory() as folder, trees(folder, options.against) as roots:
        times = {(scene, label): [] for scene in SCENES for label in roots}
        for _ in range(options.repeats):
            for scene, spec in SCENES.items():
                for label, root in roots.items():
                    times[(scene, label)].append(compile_seconds(root, spec))
    labels = list(roots)
    width = max(len(s) for s in SCENES)
    print(f"{'scene':<{width}}  " + "  ".join(f"{label + ' [s]':>14}" for label in labels))
    print(f"{'-' * width}  " + "  ".join("-" * 14 for _ in labels))
    for scene in SCENES:
        cells = [statistics.median(times[(scene, label)]) for label in labels]
        print(f"{scene:<{width}}  " + "  ".join(f"{c:>14.1f}" if c == c else f"{'-':>14}" for c in cells))


if __name__ == "__main__":
    main()

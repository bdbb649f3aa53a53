"""Every shipped scenario's plans, kept and compared bit for bit: the check that a change to how scenarios become
machines (the lowering, the elements' specs) changed no input of any compiled program.

A plan is what a run's compiled program is called with: its structure (the tree of elements, their static
fields, every leaf's shape and dtype; one compiled program per structure) and its numbers (every leaf).
Building one compiles nothing, so every scenario is checked in seconds:

- every scenario without a sweep (``scenarios/*.yaml``, ``scenarios/modelica/*.yaml``): its plan;
- every scenario with a sweep: the plans of its first, middle and last runs.

``--save FILE`` keeps each plan's structure and the bytes of its leaves (``.npz``); ``--against FILE`` builds
them again and prints a row per plan: ``same`` (structure and every leaf equal to the bit), or what differs
(the structure, or the leaves that differ and by how much); it exits 1 if any differs.

    python benchmarks/plans.py --save /tmp/plans.npz
    python benchmarks/plans.py --against /tmp/plans.npz
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import jax
import numpy as np

from hoistsim import load_scenario
from hoistsim._jax import structure_of
from hoistsim.machine.assemble import build_plan
from hoistsim.scenario.sweep_runs import SweepRuns

ROOT = Path(__file__).resolve().parents[1]


def plans() -> dict[str, object]:
    """Every plan checked, by name: a scenario's stem (``modelica/NAME``), and ``#i`` for a sweep's run i."""
    out = {}
    scenarios = ROOT / "scenarios"
    for path in sorted(scenarios.glob("*.yaml")) + sorted((scenarios / "modelica").glob("*.yaml")):
        name = path.stem if path.parent.name == "scenarios" else f"modelica/{path.stem}"
        scenario = load_scenario(path)
        runs = SweepRuns(scenario)
        if not runs.keys:
            out[name] = build_plan(scenario)[0]
            continue
        for i in sorted({0, len(runs) // 2, len(runs) - 1}):
            out[f"{name}#{i}"] = build_plan(runs.scenario(i))[0]
    return out


def kept(plan) -> dict[str, np.ndarray]:
    """A plan as arrays: its structure (text) and each leaf."""
    leaves = [np.asarray(leaf) for leaf in jax.tree.leaves(plan)]
    return {"structure": np.asarray(structure_of(plan)), **{f"leaf{i}": leaf for i, leaf in enumerate(leaves)}}


def compared(old: dict[str, np.ndarray], new: dict[str, np.ndarray]) -> str:
    """'same', or what differs between two kept plans."""
    if str(old["structure"]) != str(new["structure"]):
        return "structure differs (a program of its own)"
    differ = []
    for key in (k for k in old if k != "structure"):
        a, b = old[key], new[key]
        if a.tobytes() != b.tobytes():
            gap = np.nanmax(np.abs(a.astype(float) - b.astype(float))) if a.size else 0.0
            differ.append(f"{key} by {gap:.3g}")
    return "same" if not differ else f"{len(differ)} leaves differ: " + ", ".join(differ[:4])


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--save", type=Path, help="keep every plan here (.npz)")
    parser.add_argument("--against", type=Path, help="compare every plan with those kept here")
    args = parser.parse_args()
    built = {name: kept(plan) for name, plan in plans().items()}
    if args.save:
        np.savez(args.save, **{f"{name}|{key}": value for name, arrays in built.items()
                               for key, value in arrays.items()})
        print(f"kept {len(built)} plans in {args.save}")
    if not args.against:
        return 0
    stored = np.load(args.against)
    old: dict[str, dict[str, np.ndarray]] = {}
    for key in stored.files:
        name, part = key.split("|")
        old.setdefault(name, {})[part] = stored[key]
    bad = 0
    for name in sorted(set(old) | set(built)):
        verdict = ("missing now" if name not in built else "new" if name not in old
                   else compared(old[name], built[name]))
        bad += verdict != "same"
        print(f"{name:<48} {verdict}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())

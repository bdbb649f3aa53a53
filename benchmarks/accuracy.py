"""Largest error of the numerical runs against the closed-form solution.

Runs the generated scenes of tests/machine/test_hybrid.py at rtol 1e-10 (atol 1e-12)
and prints, per scene, the event sequence and the largest speed, event-time and
clutch-energy errors, then the worst of each.

    python benchmarks/accuracy.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

TESTS = Path(__file__).resolve().parents[1] / "tests"
sys.path[:0] = [str(TESTS), str(TESTS / "machine")]  # the tests' helpers, and test_hybrid

from helpers import reduced, scene  # noqa: E402
from test_hybrid import CASES  # noqa: E402

from hoistsim import exact_from_scenario, simulate  # noqa: E402
from hoistsim.results.report import table  # noqa: E402


def main() -> None:
    rows, worst = [], np.zeros(4)
    for i, case in enumerate(CASES):
        s = scene(**case)
        run, exact = simulate(s), exact_from_scenario(s)
        ref = exact.evaluate(run.time)
        speed = max(np.max(np.abs(run["motor_speed"] - ref["motor_speed"])),
                    np.max(np.abs(run["drum_speed"] * reduced(run).ratio - ref["output_speed"])))
        times = np.max(np.abs(run.events["time"] - [e.time for e in exact.events]), initial=0.0)
        energy = abs(run.slip_energy - exact.slip_energy) / max(exact.slip_energy, 1e-300) if exact.slip_energy else 0
        balance = run.energy_balance["relative_residual"]
        worst = np.maximum(worst, [speed, times, energy, balance])
        rows.append([f"scene{i}", ", ".join(run.events["kind"]) or "-", f"{speed:.1e}", f"{times:.1e}",
                     f"{energy:.1e}", f"{balance:.1e}"])
    rows.append(["worst", "", *(f"{w:.1e}" for w in worst)])
    print(table(["scene", "events", "speed err [rad/s]", "event time err [s]", "clutch energy rel err",
                 "energy residual"], rows, align="llrrrr"))


if __name__ == "__main__":
    main()

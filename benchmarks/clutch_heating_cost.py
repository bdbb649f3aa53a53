"""What the clutch's temperature costs a run: the force sweep with and without `clutch_heating:`, vmapped.

The scene is `scenarios/clutch_force_window.yaml` (the clutch closed at 300 rpm on the 500 kg load, 3 s):
without its `clutch_heating:` section (the canonical engagement), with it at constant friction (the
temperature a state, its peak observed), and as shipped (friction tables of temperature, their knots
restarts, an 80 degC limit).  The same engagement forces (3.8 to 12 kN), summary-only and with full
output, in process; each compiled first, then the median of five, interleaved.

    python benchmarks/clutch_heating_cost.py [--runs 1024]
"""

from __future__ import annotations

import argparse
from pathlib import Path

from elements_cost import per_run

from hoistsim import load_scenario
from hoistsim.results.report import table

SCENARIO = Path(__file__).resolve().parents[1] / "scenarios" / "clutch_force_window.yaml"


def scenes(runs: int) -> dict:
    shipped = load_scenario(SCENARIO, sweeps=[f"clutch.engagement_force=3.8 kN:12 kN:{runs}"])
    heating = shipped.clutch_heating
    constant = heating.model_copy(update={"static_friction": None, "kinetic_friction": None,
                                          "max_temperature": None})
    return {"no heating": shipped.model_copy(update={"clutch_heating": None}),
            "heating, constant friction": shipped.model_copy(update={"clutch_heating": constant}),
            "heating, fading friction, a limit": shipped}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=1024)
    runs = parser.parse_args().runs
    built = scenes(runs)
    rows = []
    for label, options in (("summary-only", {"summary_only": True}), ("full output", {})):
        cost = per_run(built, runs, **options)
        for name in built:
            rows.append([label, name, f"{cost[name]:.0f}", f"{cost[name] / cost['no heating']:.2f}x"])
    print(f"{runs} runs a sweep, in process, medians of 5 after compiling")
    print(table(["output", "scene", "us/run", "against no heating"], rows, align="llrr"))


if __name__ == "__main__":
    main()

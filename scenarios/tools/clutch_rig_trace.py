"""The synthetic rig trace of scenarios/clutch_rig.yaml: the run at known friction, measured with noise.

The clutch's true coefficients are static 0.33 and kinetic 0.09 (the scenario starts from the
catalogue's 0.3 and 0.1).  The run's motor and drum speeds are read every 10 ms from 0 to 3 s, in rpm,
with Gaussian noise of 1 rpm and 0.2 rpm (seeded: the same file every time).  Run it to write the file:

    python scenarios/tools/clutch_rig_trace.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hoistsim import load_scenario, simulate

HERE = Path(__file__).resolve().parent
TRUE = {"clutch.static_friction": 0.33, "clutch.kinetic_friction": 0.09}
NOISE_RPM = {"motor_speed": 1.0, "drum_speed": 0.2}
SEED = 20261126


def main() -> None:
    overrides = [f"{key}={value}" for key, value in TRUE.items()] + ["simulation.output_interval=10 ms"]
    run = simulate(load_scenario(HERE.parent / "clutch_rig.yaml", overrides=overrides))
    rows = run.grid_rows()  # the 10 ms grid's rows (event rows left out)
    rng = np.random.default_rng(SEED)
    columns = {name: run.series[name][rows] * 60 / (2 * np.pi) + rng.normal(0.0, noise, rows.size)
               for name, noise in NOISE_RPM.items()}
    lines = ["time [s]," + ",".join(f"{name} [rpm]" for name in columns)]
    lines += [f"{t:.2f}," + ",".join(f"{columns[name][k]:.3f}" for name in columns)
              for k, t in enumerate(run.time[rows])]
    (HERE.parent / "clutch_rig_trace.csv").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()

"""What accuracy costs in time: the work-precision study.

Three canonical start-ups, each solved by every method at a range of
tolerances and measured against the closed-form solution:

- hoistsim's hybrid loop, stepping diffrax's solvers (explicit and implicit Runge-Kutta);
- the same hybrid model on scipy's solve_ivp with event restarts;
- the regularised (tanh) friction model, explicit and implicit, several widths;
- the closed-form solution itself, the floor of cost.

Errors: the largest speed error on the output grid (both shafts), the largest
error in a switch time (NaN when a method gets the sequence of switches wrong)
and the relative error in clutch heat.  Times: warm, min and median of repeats,
with the first call's extra (compilation) reported apart.

    python benchmarks/work_precision.py            # the full study -> benchmarks/results/
    hoistsim bench --smoke                         # a few tolerances, seconds
"""

from __future__ import annotations

import csv
import math
import statistics
import time
from dataclasses import asdict, dataclass, fields
from pathlib import Path

import numpy as np

from ..references.exact import exact_from_scenario
from ..references.model import Machine
from ..references.regularised import simulate_regularised
from ..references.scipy_reference import solve_scenario_with_scipy
from ..running.simulation import simulate
from ..scenario.loading import scenario_from_dict

_MACHINE = {
    "motor": {"stall_torque": "500 N*m", "no_load_speed": "300 rpm", "inertia": "0.9 kg*m^2"},
    "clutch": {"inner_radius": "20 cm", "outer_radius": "24 cm", "half_angle": "25 deg",
               "static_friction": 0.3, "kinetic_friction": 0.1},
    "gears": {"pinion_teeth": 17, "wheel_teeth": 90, "module": "4 mm"},
    "drum": {"diameter": "40 cm", "inertia": "40 kg*m^2"},
}

# name -> (description, scenario sections beyond the machine)
SCENES = {
    "slip_then_lock": ("motor idling at 300 rpm, clutch closed at 6 kN on 500 kg: slips, locks at 0.21 s", {
        "clutch": {"engagement_force": "6 kN"}, "load": {"mass": "500 kg"},
        "initial": {"motor_speed": "300 rpm"}, "simulation": {"duration": "2 s", "output_interval": "1 ms"}}),
    "engage_with_brake": ("clutch ramped to 5 kN at 0.5-0.6 s against the brake, released at 0.6 s", {
        "clutch": {"engagement_force": [["0 s", "0 N"], ["0.5 s", "0 N"], ["0.6 s", "5000 N"]]},
        "load": {"mass": "500 kg"}, "brake": {"release_time": "0.6 s"},
        "simulation": {"duration": "3 s", "output_interval": "1 ms"}}),
    "ramp_unlock": ("force ramped up, down and up again on 200 kg: lock, unlock, lock", {
        "clutch": {"engagement_force": [["0 s", "0 N"], ["0.5 s", "6000 N"], ["1.5 s", "6000 N"],
                                        ["2 s", "500 N"], ["2.5 s", "500 N"], ["3 s", "6000 N"]]},
        "load": {"mass": "200 kg"}, "simulation": {"duration": "4 s", "output_interval": "1 ms"}}),
}

HYBRID_SOLVERS = ("tsit5", "dopri5", "dopri8", "bosh3", "kvaerno5")
SCIPY_METHODS = ("RK45", "DOP853", "LSODA", "Radau")
REGULARISED = (("tsit5", "explicit"), ("kvaerno5", "implicit"))
WIDTHS = (1.0, 0.1, 0.01, 0.001)  # rad/s
# right-hand-side evaluations per step (first-same-as-last counted once); implicit: not fixed
STAGES = {"tsit5": 6, "dopri5": 6, "dopri8": 12, "bosh3": 3}


@dataclass
class Row:
    scene: str
    family: str  # hybrid (hoistsim), scipy, regularised, exact
    method: str
    setting: str  # rtol, or the smoothing width
    rtol: float
    speed_error: float  # rad/s
    switch_time_error: float  # s; NaN when the switches differ
    switches_match: bool
    clutch_energy_error: float  # relative
    steps: float
    evaluations: float  # NaN where it is not fixed per step
    time_min: float  # s
    time_median: float  # s
    compile_time: float  # s (first call less the median)


def scene(name: str, rtol: float = 1e-8, solver: str = "tsit5"):
    description, sections = SCENES[name]
    data = {"name": name, "description": description}
    for key, value in {**_MACHINE, **sections}.items():
        data[key] = {**_MACHINE.get(key, {}), **value} if isinstance(value, dict) else value
    data["simulation"] = {**data["simulation"], "rtol": rtol, "atol": rtol * 1e-2, "solver": solver}
    return scenario_from_dict(data, name=name)


def _timed(func, repeats: int):
    start = time.perf_counter()
    result = func()
    first = time.perf_counter() - start
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    median = statistics.median(times) if times else first
    return result, min(times, default=first), median, max(first - median, 0.0)


def _errors(exact, t, motor, output, energy, switches):
    ref = exact.evaluate(t)
    speed = float(max(np.max(np.abs(motor - ref["motor_speed"])), np.max(np.abs(output - ref["output_speed"]))))
    expected = [(e.time, e.kind) for e in exact.events if e.kind in ("lock", "unlock", "reversal")]
    got = [(tt, k) for tt, k in switches if k in ("lock", "unlock", "reversal")]
    match = [k for _, k in got] == [k for _, k in expected]
    switch_error = max((abs(a[0] - b[0]) for a, b in zip(got, expected)), default=0.0) if match else math.nan
    heat = abs(energy - exact.slip_energy) / exact.slip_energy if exact.slip_energy else abs(energy)
    return speed, switch_error, match, float(heat)


def run_hybrid(name, solver, rtol, exact, repeats):
    s = scene(name, rtol, solver)
    run, best, median, compile_time = _timed(lambda: simulate(s), repeats)
    ratio = Machine.from_scenario(s).reduced().ratio
    errors = _errors(exact, run.time, run["motor_speed"], run["drum_speed"] * ratio,
                     run.slip_energy, list(zip(run.events["time"], run.events["kind"])))
    steps = run.stats["steps"]
    return Row(name, "hybrid (hoistsim)", solver, f"{rtol:.0e}", rtol, *errors, steps,
               steps * STAGES[solver] if solver in STAGES else math.nan, best, median, compile_time)


def run_scipy(name, method, rtol, exact, repeats):
    s = scene(name, rtol)
    (events, evaluate, _, stats), best, median, _ = _timed(
        lambda: solve_scenario_with_scipy(s, method=method, dense=True), repeats)
    t = np.arange(0.0, s.simulation.duration + 1e-12, s.simulation.output_interval)
    states = evaluate(t)
    errors = _errors(exact, t, states[0], states[1], states[3, -1], events)
    return Row(name, "scipy", method, f"{rtol:.0e}", rtol, *errors, stats["steps"], stats["evaluations"],
               best, median, 0.0)


def run_regularised(name, solver, width, exact, repeats, rtol=1e-8):
    s = scene(name, rtol)
    (t, states, stats), best, median, compile_time = _timed(lambda: simulate_regularised(s, width, solver), repeats)
    if not stats["finished"]:
        return Row(name, "regularised", f"tanh {solver}", f"width {width:g}", rtol, math.nan, math.nan, False,
                   math.nan, stats["steps"], math.nan, best, median, compile_time)
    # no modes, so no switches: only the trajectory and the heat can be compared
    speed, _, _, heat = _errors(exact, t, states["motor.speed"], states["pinion.speed"], states["clutch_energy"][-1],
                                [])
    return Row(name, "regularised", f"tanh {solver}", f"width {width:g}", rtol, speed, math.nan, False, heat,
               stats["steps"], stats["steps"] * STAGES.get(solver, math.nan), best, median, compile_time)


def run_exact(name, repeats):
    s = scene(name)
    grid = np.arange(0.0, s.simulation.duration + 1e-12, s.simulation.output_interval)
    _, best, median, _ = _timed(lambda: exact_from_scenario(s).evaluate(grid), repeats)
    return Row(name, "exact", "closed form", "-", math.nan, 0.0, 0.0, True, 0.0, math.nan, math.nan,
               best, median, 0.0)


def study(smoke: bool = False, progress=print) -> list[Row]:
    if smoke:
        scenes, tolerances, scipy_tolerances = ["slip_then_lock"], [1e-5, 1e-9], [1e-5, 1e-8]
        solvers, methods, regularised, widths, repeats = ("tsit5",), ("RK45",), REGULARISED[:1], (0.1,), 1
    else:
        scenes, tolerances = list(SCENES), [10.0**-k for k in range(3, 13)]
        scipy_tolerances = [10.0**-k for k in range(3, 11)]
        solvers, methods, regularised, widths, repeats = HYBRID_SOLVERS, SCIPY_METHODS, REGULARISED, WIDTHS, 5
    rows = []
    for name in scenes:
        exact = exact_from_scenario(scene(name))
        rows.append(run_exact(name, repeats))
        for solver in solvers:
            for rtol in tolerances:
                rows.append(run_hybrid(name, solver, rtol, exact, repeats))
            progress(f"  {name}: {solver} done")
        for method in methods:
            for rtol in scipy_tolerances:
                rows.append(run_scipy(name, method, rtol, exact, max(1, repeats // 2)))
            progress(f"  {name}: scipy {method} done")
        for solver, _ in regularised:
            for width in widths:
                rows.append(run_regularised(name, solver, width, exact, repeats))
            progress(f"  {name}: tanh {solver} done")
    return rows


def write_csv(rows: list[Row], path: Path) -> None:
    with open(path, "w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(asdict(rows[0])))
        writer.writeheader()
        for row in rows:
            writer.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in asdict(row).items()})


def read_csv(path: Path) -> list[Row]:
    """The rows of a study's CSV (to redraw its figure without running it again)."""
    kinds = {f.name: f.type for f in fields(Row)}
    with open(path, newline="") as handle:
        return [Row(**{k: (v if kinds[k] == "str" else v == "True" if kinds[k] == "bool" else float(v))
                       for k, v in record.items()}) for record in csv.DictReader(handle)]


def write_figure(rows: list[Row], path: Path) -> None:
    """Error against warm time per run, a panel per scene; the default solver's points labelled by rtol.

    Every point of tsit5 (the default) and of the regularised runs (by smoothing
    width) carries its setting; the other lines, their loosest and tightest.
    The closed form's evaluation time is drawn for reference: it is a numpy
    evaluation of the piecewise solution, not a bound on what a solver can cost.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = list(dict.fromkeys(r.scene for r in rows))
    fig, axes = plt.subplots(1, len(scenes), figsize=(5.6 * len(scenes), 5.6), sharey=True, squeeze=False,
                             layout="constrained")
    styles = {"hybrid (hoistsim)": "-", "scipy": "--", "regularised": ":"}
    for ax, name in zip(axes[0], scenes):
        mine = [r for r in rows if r.scene == name]
        for (family, method) in dict.fromkeys((r.family, r.method) for r in mine if r.family != "exact"):
            line = [r for r in mine if (r.family, r.method) == (family, method) and np.isfinite(r.speed_error)]
            if not line:
                continue
            drawn = ax.plot([r.time_median for r in line], [max(r.speed_error, 1e-16) for r in line],
                            styles[family], marker="o", ms=3, lw=1.3,
                            label=f"{method}" + (" (scipy)" if family == "scipy" else ""))
            labelled = line if method == "tsit5" or family == "regularised" else [line[0], line[-1]]
            for r in labelled:
                ax.annotate(r.setting, (r.time_median, max(r.speed_error, 1e-16)), xytext=(3, 2),
                            textcoords="offset points", fontsize=6, color=drawn[0].get_color())
        for r in mine:
            if r.family == "exact":
                ax.axvline(r.time_median, color="k", lw=0.8, ls="-.",
                           label="closed form, evaluated with numpy (for reference)")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(name.replace("_", " "), fontsize=10)
        ax.set_xlabel("warm time per run [s] (median)")
        ax.grid(True, which="both", lw=0.3, alpha=0.5)
    axes[0][0].set_ylabel("largest speed error on the output grid [rad/s]")
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncols=6, fontsize=8, frameon=False)
    fig.suptitle("What accuracy costs: error against time, against the closed-form solution "
                 "(points labelled by rtol; regularised lines by smoothing width in rad/s)",
                 x=0.01, ha="left", fontsize=11)
    fig.savefig(path, dpi=140)
    plt.close(fig)


def table_text(rows: list[Row]) -> str:
    from ..results.report import table

    return table(["scene", "method", "setting", "speed err", "switch err", "heat err", "steps", "median [ms]",
                  "compile [s]"],
                 [[r.scene, r.method, r.setting, f"{r.speed_error:.1e}", f"{r.switch_time_error:.1e}",
                   f"{r.clutch_energy_error:.1e}", f"{r.steps:.0f}", f"{r.time_median * 1e3:.2f}",
                   f"{r.compile_time:.1f}"] for r in rows], align="lllrrrrrr")


def main(smoke: bool = False, output: str | Path = "benchmarks/results") -> list[Row]:
    rows = study(smoke=smoke)
    print(table_text(rows))
    if not smoke:
        folder = Path(output)
        folder.mkdir(parents=True, exist_ok=True)
        write_csv(rows, folder / "work_precision.csv")
        write_figure(rows, folder / "work_precision.png")
        print(f"wrote {folder / 'work_precision.csv'} and {folder / 'work_precision.png'}")
    return rows

"""What the periodic regime costs: a long ripple run, the flywheel command, and scipy on the same machine.

Scene: scenarios/motor_ripple_tredgold.yaml (the exercise-6 hoist lifting steadily, its motor's
torque rippling twice a turn; the clutch stays locked).  A machine period is a turn of the motor,
about 0.318 s at the steady 19.77 rad/s.  Every measurement compiles first, then times: the first
call (tracing, compiling and the run) and the median of 3 warm calls.

- long runs: ``simulate`` over 50 and 500 periods, with output rows every 0.05 s and every 5 s:
  wall time, time per period, passes, steps, the energy balance's relative residual;
- exactness: the spread, (max - min) / mean, of each period's mean, largest and smallest speed
  over the last 400 periods of the 500-period run, and periods 50 and 500 side by side;
- the peer: scipy ``solve_ivp`` (DOP853, rtol 1e-8, atol 1e-10) on the same locked machine
  written out by hand as one rigid body at the motor shaft, over the same duration (plain
  integration: no events, no dense output while timed); its speeds against hoistsim's rows, and
  both against a run at rtol 1e-13 (not timed);
- the flywheel command: ``size_flywheel`` for irregularities of 0.02 and 0.005 (goal: under 5 s warm).

Writes benchmarks/results/periodic_cost.csv.

    python benchmarks/periodic_cost.py
"""

from __future__ import annotations

import argparse
import csv
import math
import statistics
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

from hoistsim import simulate
from hoistsim.results.report import table
from hoistsim.scenario.loading import load_scenario
from hoistsim.studies.flywheel import size_flywheel

ROOT = Path(__file__).resolve().parents[1]
SCENE = ROOT / "scenarios" / "motor_ripple_tredgold.yaml"
REPEATS = 3
PERIOD_COUNTS = (50, 500)
# Rows every 0.05 s are coarse beside the period; every 5 s is next to none.  Both are measured
# because each pass of the restart loop is handed the whole output grid: a pass costs more the
# more rows the run has, and with a fixed interval the rows grow with the duration as the passes do.
COARSE, SPARSE = 0.05, 5.0
INTERVALS = (COARSE, SPARSE)
LAST = 400  # periods checked for exactness at the end of the long run
TARGETS = (0.02, 0.005)  # irregularities the flywheel command is asked for

# The same machine by hand: everything at the motor shaft, the clutch locked, gears ideal.
GEAR = 90 / 17
INERTIA = 3.0407407407407407  # kg*m^2: motor 0.9 + (drum 40 + 500 kg * (0.2 m)^2) / GEAR^2
STALL = 500.0  # N*m
NO_LOAD = 10 * math.pi  # rad/s (300 rpm)
LOAD = 500 * 9.81 * 0.2 / GEAR  # N*m, the load's weight on the drum, at the motor
MEAN_SPEED = NO_LOAD * (1 - LOAD / STALL)  # rad/s, the steady lifting speed (19.77): the start
PERIOD_TIME = 2 * math.pi / MEAN_SPEED  # s, a first guess of a period's length


def clock(func):
    start = time.perf_counter()
    value = func()
    return time.perf_counter() - start, value


def timed(func, repeats: int = REPEATS):
    """The first call (with any compiling), the median of ``repeats`` warm calls, and the last answer."""
    first, value = clock(func)
    warm = []
    for _ in range(repeats):
        seconds, value = clock(func)
        warm.append(seconds)
    return first, statistics.median(warm), value


def lasting(scenario, periods: int, interval: float):
    # Period 1 starts at the first whole turn after t = 0 and the last must end before the run does:
    # three periods' margin leaves at least ``periods`` whole ones (the table says how many).
    simulation = scenario.simulation.model_copy(update={"duration": (periods + 3) * PERIOD_TIME,
                                                        "output_interval": interval})
    return scenario.model_copy(update={"simulation": simulation})


def long_run(scenario, periods: int, interval: float) -> dict:
    first, warm, result = timed(lambda: simulate(scenario))
    count = int(result.periodic.regime.table["period"].size)
    assert count >= periods, f"{count} whole periods in {scenario.simulation.duration:g} s, {periods} wanted"
    return {"periods": count, "interval": interval, "duration": scenario.simulation.duration,
            "rows": int(result.time.size), "first": first, "warm": warm, "per_period": warm / count,
            "passes": int(result.stats["segments"]), "steps": int(result.stats["steps"]),
            "residual": float(result.energy_balance["relative_residual"]), "result": result}


def rigid_body(t, y):
    theta, omega = y
    ripple = 120 * math.sin(2 * theta) + 30 * math.sin(4 * theta + math.pi / 6)
    return [omega, (STALL * (1 - omega / NO_LOAD) + ripple - LOAD) / INERTIA]


def scipy_run(duration: float, dense: bool = False, rtol: float = 1e-8, atol: float = 1e-10):
    return solve_ivp(rigid_body, (0.0, duration), [0.0, MEAN_SPEED], method="DOP853", rtol=rtol, atol=atol,
                     dense_output=dense)


def spread(column) -> float:
    return float((np.max(column) - np.min(column)) / np.mean(column))


def unit(name: str) -> str:
    return "1" if name == "irregularity" else "rad/s"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default=str(Path(__file__).parent / "results"), help="folder for the CSV")
    args = parser.parse_args()
    scenario = load_scenario(SCENE)
    csv_rows = []  # (section, case, measure, value, unit)

    # 1. Long runs.  Each (duration, rows) shape is a program of its own, so each compiles on its first call.
    runs = {(n, dt): long_run(lasting(scenario, n, dt), n, dt) for dt in INTERVALS for n in PERIOD_COUNTS}
    print(f"{SCENE.relative_to(ROOT)}: simulate, first call and median of {REPEATS} warm calls\n")
    print(table(["periods", "rows every [s]", "output rows", "first call [s]", "warm [s]", "per period [ms]",
                 "passes", "steps", "energy residual"],
                [[r["periods"], f"{r['interval']:g}", r["rows"], f"{r['first']:.2f}", f"{r['warm']:.3f}",
                  f"{1e3 * r['per_period']:.2f}", r["passes"], r["steps"], f"{r['residual']:.1e}"]
                 for r in runs.values()]))
    for r in runs.values():
        case = f"{r['periods']} periods, rows every {r['interval']:g} s"
        csv_rows += [("long run", case, key, r[key], units) for key, units in
                     (("periods", "1"), ("duration", "s"), ("rows", "1"), ("first", "s"), ("warm", "s"),
                      ("per_period", "s"), ("passes", "1"), ("steps", "1"), ("residual", "1"))]
    few, many = PERIOD_COUNTS
    print()
    for dt in INTERVALS:
        a, b = runs[few, dt], runs[many, dt]
        print(f"rows every {dt:g} s: {b['periods'] / a['periods']:.1f}x the periods cost {b['warm'] / a['warm']:.1f}x "
              f"the time ({b['per_period'] / a['per_period']:.1f}x per period)")

    # 2. Exactness: a settled periodic regime repeats, so every period of the long run should agree.
    main_run = runs[many, COARSE]
    periods = main_run["result"].periodic.regime.table
    at = {n: int(np.flatnonzero(periods["period"] == n)[0]) for n in (50, 500)}
    spreads, exact_rows = {}, []
    for name in ("mean_speed", "max_speed", "min_speed", "irregularity"):
        column = periods[name]
        spreads[name] = spread(column[-LAST:])
        p50, p500 = float(column[at[50]]), float(column[at[500]])
        exact_rows.append([name, f"{spreads[name]:.1e}", f"{p50:.12g}", f"{p500:.12g}",
                           f"{abs(p500 - p50) / abs(p50):.1e}"])
        csv_rows += [("exactness", name, f"spread_last_{LAST}_periods", spreads[name], "1"),
                     ("exactness", name, "period_50", p50, unit(name)),
                     ("exactness", name, "period_500", p500, unit(name))]
    print(f"\nthe {main_run['periods']}-period run (rows every {COARSE:g} s), per period; speeds in rad/s\n")
    print(table(["quantity", f"spread, last {LAST}", "period 50", "period 500", "relative difference"], exact_rows))

    # 3. The peer, on the long run's duration.  Timed without dense output (the cheapest scipy call);
    # one more call with it gives the speeds at hoistsim's rows.  Over hundreds of periods both drift
    # in phase (the machine's angle has no restoring force, so an error in it stays), which shows as
    # a speed difference: a run at rtol 1e-13 (not timed) tells each one's share.
    duration = main_run["duration"]
    peer_first, peer_warm, sol = timed(lambda: scipy_run(duration))
    result = main_run["result"]
    speed = result["motor_speed"]
    reference = scipy_run(duration, dense=True).sol(result.time)[1]
    tight = scipy_run(duration, dense=True, rtol=1e-13, atol=1e-13).sol(result.time)[1]
    difference = np.abs(speed - reference) / np.abs(reference)
    drift = {"hoistsim": np.abs(speed - tight) / tight, "scipy": np.abs(reference - tight) / tight}
    ratio = {dt: runs[many, dt]["warm"] / peer_warm for dt in INTERVALS}
    peer_rows = [[f"hoistsim, rows every {dt:g} s", f"{runs[many, dt]['warm']:.3f}",
                  f"{1e3 * runs[many, dt]['per_period']:.2f}", f"{ratio[dt]:.2f}", runs[many, dt]["steps"]]
                 for dt in INTERVALS]
    peer_rows.append(["scipy DOP853", f"{peer_warm:.3f}", f"{1e3 * peer_warm / main_run['periods']:.2f}", "1.00",
                      f"{sol.t.size - 1} ({sol.nfev} evaluations)"])
    print(f"\nthe peer: {main_run['periods']} periods ({duration:.2f} s), rtol 1e-8, atol 1e-10, "
          f"median of {REPEATS} warm calls\n")
    print(table(["solver", "warm [s]", "per period [ms]", "ratio to scipy", "steps"], peer_rows))
    checks = [result.time.size * k // 4 for k in range(4)] + [result.time.size - 1]
    print("\nmotor speed at hoistsim's rows, against scipy's dense output (relative differences)\n")
    print(table(["time [s]", "hoistsim [rad/s]", "scipy [rad/s]", "hoistsim - scipy", "hoistsim - rtol 1e-13",
                 "scipy - rtol 1e-13"],
                [[f"{result.time[i]:.3f}", f"{speed[i]:.12g}", f"{reference[i]:.12g}", f"{difference[i]:.1e}",
                  f"{drift['hoistsim'][i]:.1e}", f"{drift['scipy'][i]:.1e}"] for i in checks]
                + [[f"largest, all {result.time.size} rows", "", "", f"{np.max(difference):.1e}",
                    f"{np.max(drift['hoistsim']):.1e}", f"{np.max(drift['scipy']):.1e}"]]))
    csv_rows += [("peer", "scipy DOP853", "first", peer_first, "s"),
                 ("peer", "scipy DOP853", "warm", peer_warm, "s"),
                 ("peer", "scipy DOP853", "per_period", peer_warm / main_run["periods"], "s"),
                 ("peer", "scipy DOP853", "steps", sol.t.size - 1, "1"),
                 ("peer", "scipy DOP853", "evaluations", sol.nfev, "1"),
                 *[("peer", f"hoistsim / scipy, rows every {dt:g} s", "ratio", ratio[dt], "1") for dt in INTERVALS],
                 ("peer", "hoistsim vs scipy", "largest_relative_speed_difference", float(np.max(difference)), "1"),
                 *[("peer", f"{name} vs scipy rtol 1e-13", "largest_relative_speed_difference", float(np.max(d)), "1")
                   for name, d in drift.items()]]

    # 4. The flywheel command on the scene as it stands (its own duration and rows).
    sizings = []
    for target in TARGETS:
        first, warm, sizing = timed(lambda: size_flywheel(scenario, target))
        sizings.append((target, first, warm, sizing))
        case = f"irregularity {target:g}"
        csv_rows += [("flywheel", case, "first", first, "s"), ("flywheel", case, "warm", warm, "s"),
                     ("flywheel", case, "runs", len(sizing.candidates), "1"),
                     *[("flywheel", case, key, getattr(sizing, key), units) for key, units in
                       (("flywheel_inertia_tredgold", "kg*m^2"), ("flywheel_inertia", "kg*m^2"),
                        ("irregularity_with_tredgold_flywheel", "1"), ("irregularity_with_flywheel", "1"))]]
    print(f"\nthe flywheel command (size_flywheel), first call and median of {REPEATS} warm calls; "
          "goal: under 5 s warm\n")
    print(table(["target", "first call [s]", "warm [s]", "runs", "Tredgold's [kg*m^2]", "simulated [kg*m^2]",
                 "delta, Tredgold's", "delta, simulated"],
                [[f"{t:g}", f"{first:.2f}", f"{warm:.2f}", len(s.candidates), f"{s.flywheel_inertia_tredgold:.4f}",
                  f"{s.flywheel_inertia:.4f}", f"{s.irregularity_with_tredgold_flywheel:.6f}",
                  f"{s.irregularity_with_flywheel:.6f}"] for t, first, warm, s in sizings]))

    output = Path(args.output)
    output.mkdir(parents=True, exist_ok=True)
    with open(output / "periodic_cost.csv", "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["section", "case", "measure", "value", "unit"])
        writer.writerows(csv_rows)

    lines = ["", "summary"]
    for dt in INTERVALS:
        a, b = runs[few, dt], runs[many, dt]
        lines.append(f"  {b['periods']} periods, rows every {dt:g} s: {b['warm']:.2f} s warm, "
                     f"{1e3 * b['per_period']:.2f} ms a period ({1e3 * a['per_period']:.2f} ms over {a['periods']}); "
                     f"first call {b['first']:.1f} s; {b['passes']} passes, {b['steps']} steps; "
                     f"energy residual {b['residual']:.1e}; {ratio[dt]:.2f}x scipy's time")
    lines.append(f"  scipy DOP853: {peer_warm:.3f} s warm ({1e3 * peer_warm / main_run['periods']:.2f} ms a period); "
                 f"motor speeds agree to {np.max(difference):.1e} "
                 f"(against rtol 1e-13: hoistsim {np.max(drift['hoistsim']):.1e}, scipy {np.max(drift['scipy']):.1e})")
    lines.append(f"  last {LAST} periods: spread of mean/max/min speed at most "
                 f"{max(spreads[k] for k in ('mean_speed', 'max_speed', 'min_speed')):.1e}")
    for t, first, warm, s in sizings:
        lines.append(f"  flywheel for {t:g}: {warm:.2f} s warm ({first:.1f} s first call), {len(s.candidates)} runs; "
                     f"{s.flywheel_inertia:.4f} kg*m^2 (Tredgold: {s.flywheel_inertia_tredgold:.4f})")
    lines.append(f"  written: {output / 'periodic_cost.csv'}")
    print("\n".join(lines))


if __name__ == "__main__":
    main()

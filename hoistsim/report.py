"""Tables for the terminal: aligned columns, units in the headers."""

from __future__ import annotations

import math

from .model import Machine


def table(headers: list[str], rows: list[list[str]], align: str | None = None) -> str:
    """A plain-text table; ``align`` has one 'l' or 'r' per column (default: first left, rest right)."""
    align = align or "l" + "r" * (len(headers) - 1)
    widths = [max(len(str(x)) for x in col) for col in zip(headers, *rows)]

    def line(cells):
        return "  ".join(str(c).ljust(w) if a == "l" else str(c).rjust(w)
                         for c, w, a in zip(cells, widths, align)).rstrip()

    rule = "  ".join("-" * w for w in widths)
    return "\n".join([line(headers), rule, *(line(r) for r in rows)])


def fmt(value: float, digits: int = 4) -> str:
    if isinstance(value, bool):
        return "yes" if value else "no"
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, int):
        return str(value)
    if value != 0 and (abs(value) >= 1e5 or abs(value) < 1e-3):
        return f"{value:.{digits - 1}e}"
    return f"{value:.{digits}g}"


def run_table(results) -> str:
    headers = ["run", "lock-up [s]", "slip energy [J]", "peak torque [N*m]", "lowest load [m]",
               "final load [m]", "motor [rpm]", "events", "energy residual"]
    rows = []
    for r in results:
        s = r.summary
        rows.append([
            r.label or r.name,
            fmt(s["lockup_time"]),
            fmt(s["slip_energy"]),
            fmt(s["peak_clutch_torque"]),
            fmt(s["lowest_load_position"]),
            fmt(s["final_load_position"]),
            fmt(s["final_motor_speed"] * 30 / math.pi),
            ", ".join(r.events["kind"]) or "-",
            f"{s['energy_relative_residual']:.1e}",
        ])
    return table(headers, rows)


def reduced_model_table(scenario) -> str:
    machine = Machine.from_scenario(scenario)
    d = machine.reduced()
    force = scenario.clutch.engagement_force
    peak = max(force.forces)
    rows = [
        ["J_a", "motor-side inertia", fmt(d.motor_inertia), "kg*m^2"],
        ["J_b", "output-side inertia (at the pinion)", fmt(d.output_inertia), "kg*m^2"],
        ["tau", "gear ratio z2/z1", fmt(d.ratio), "-"],
        ["T_L", "load torque at the pinion", fmt(d.load_torque), "N*m"],
        ["c", "clutch constant n r_m / sin(beta)", fmt(d.clutch_constant), "m"],
        ["T_s", f"static capacity at {fmt(peak)} N", fmt(d.static_capacity(peak)), "N*m"],
        ["T_k", f"kinetic torque at {fmt(peak)} N", fmt(d.kinetic_torque(peak)), "N*m"],
    ]
    return table(["symbol", "quantity", "value", "unit"], rows, align="llrl")

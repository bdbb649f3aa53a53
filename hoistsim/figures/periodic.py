"""Figures of the periodic regime: the turning-moment diagram, speed over a period, delta against flywheel.

matplotlib is imported by the callers (:mod:`hoistsim.figures.files`, the flywheel command) only.
"""

from __future__ import annotations

import math

import numpy as np

RPM = 30.0 / math.pi
DEG = 180.0 / math.pi
_DRIVING, _RESISTING, _AREA = "#b2182b", "#2166ac", "#f4a582"


def _in_turn(angle, start, end, period):
    """Whether angles lie in the cyclic interval from start to end (within one period)."""
    return np.mod(angle - start, period) <= np.mod(end - start, period)


def turning_moment_axes(ax, diagram: dict) -> None:
    """Driving and resisting torque over one period, the Delta E_max area shaded, theta_1 and theta_2 marked."""
    a = diagram["attrs"]
    angle = diagram["angle"]
    period = angle[-1]
    driving, resisting = diagram["driving_torque"], diagram["resisting_torque"]
    theta1, theta2 = float(a["min_speed_angle"]), float(a["max_speed_angle"])
    ax.plot(angle * DEG, driving, color=_DRIVING, lw=1.6, label="driving torque M'_m (motor)")
    ax.plot(angle * DEG, resisting, color=_RESISTING, lw=1.6, label="resisting torque M'_r (load; inertia torques of reciprocating parts at w_m)")
    inside = _in_turn(angle, theta1, theta2, period)
    surplus = inside & (driving >= resisting)
    ax.fill_between(angle * DEG, resisting, driving, where=surplus, color=_AREA, alpha=0.55, lw=0,
                    interpolate=True, label="surplus (speeds up) between theta_1 and theta_2")
    ax.fill_between(angle * DEG, resisting, driving, where=inside & ~surplus, color="#92c5de", alpha=0.55, lw=0,
                    interpolate=True, label="deficit (slows down) between them")
    ax.plot([], [], " ", label=f"net area theta_1 -> theta_2: dE_max = {float(a['energy_fluctuation']):.4g} J")
    for theta, name, what in ((theta1, "theta_1", "w_min"), (theta2, "theta_2", "w_max")):
        ax.axvline(theta * DEG, color="0.25", lw=0.9, ls="--")
        right = theta > 0.8 * period  # near the right edge: write it on the left of the line
        ax.annotate(f"{name} = {theta * DEG:.1f} deg\n({what})", (theta * DEG, 1.0),
                    xycoords=("data", "axes fraction"), xytext=(-3 if right else 3, -4),
                    textcoords="offset points", va="top", ha="right" if right else "left", fontsize=8)
    ax.set_xlim(0.0, period * DEG)
    ax.set_xlabel("motor angle from the start of the period [deg]")
    ax.set_ylabel("torque at the motor shaft [N*m]")
    ax.set_title(f"turning-moment diagram at w_m = {float(a['mean_speed']) * RPM:.5g} rpm; "
                 f"Tredgold: delta = {float(a['irregularity']):.4g} with I = {float(a['inertia']):.4g} kg*m^2",
                 fontsize=10, loc="left")
    ax.grid(True, lw=0.4, alpha=0.6)


def speed_over_period_axes(ax, run: dict) -> None:
    """Motor speed against angle over the first analysed period, with its extremes, mean and delta."""
    periods, attrs = run["periods"], run["attrs"]
    first = int(np.flatnonzero(periods["analysed"] == 1)[0])
    start, end = periods["start_time"][first], periods["end_time"][first]
    rows = (run["time"] >= start) & (run["time"] <= end)
    angle = (run["motor_angle"][rows] - periods["start_angle"][first]) * DEG
    speed = run["motor_speed"][rows] * RPM
    top, bottom = periods["max_speed"][first] * RPM, periods["min_speed"][first] * RPM
    mean = periods["mean_speed"][first] * RPM
    ax.plot(angle, speed, color="#1f4e79", lw=1.6, label="motor speed (simulated)")
    for value, name, style in ((top, "w_max", "--"), (mean, "w_mean (over angle)", "-"),
                               (bottom, "w_min", "--")):
        ax.axhline(value, color="0.35", lw=0.9, ls=style)
        ax.annotate(f"{name} = {value:.5g} rpm", (1.0, value), xycoords=("axes fraction", "data"),
                    xytext=(-4, 3), textcoords="offset points", ha="right", fontsize=8)
    ax.plot([periods["max_speed_angle"][first] * DEG], [top], "^", color=_DRIVING, ms=6)
    ax.plot([periods["min_speed_angle"][first] * DEG], [bottom], "v", color=_RESISTING, ms=6)
    delta = float(attrs.get("irregularity", math.nan))
    tredgold = float(attrs.get("irregularity_tredgold", math.nan))
    ax.set_title(f"motor speed over period {first + 1} (the regime settled after "
                 f"{_periods(int(attrs.get('settling_periods', first)))}): delta = {delta:.4g} simulated, "
                 f"{tredgold:.4g} by Tredgold", fontsize=10, loc="left")
    ax.set_xlim(0.0, float(periods["attrs"]["period"]) * DEG)
    ax.set_xlabel("motor angle from the start of the period [deg]")
    ax.set_ylabel("motor speed [rpm]")
    ax.grid(True, lw=0.4, alpha=0.6)


def _periods(n: int) -> str:
    return f"{n} period" if n == 1 else f"{n} periods"


def periodic_figure(run: dict, plt):
    """The turning-moment diagram above the speed over the same period."""
    fig, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(9, 8))
    turning_moment_axes(top, run["turning_moment"])
    speed_over_period_axes(bottom, run)
    top.set_xlabel("")
    name = str(run["attrs"].get("name", ""))
    fig.suptitle(f"{name}: periodic regime of the motor shaft", fontsize=11, x=0.01, ha="left")
    # the diagram's legend below the figure, where it hides neither curve nor label
    fig.legend(*top.get_legend_handles_labels(), loc="lower center", ncol=2, fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    return fig


def flywheel_figure(sizing, output, title: str = "") -> None:
    """delta against the flywheel's inertia, simulated (the candidates run) and by Tredgold."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.ticker import ScalarFormatter

    fig, (ax, ax_gap) = plt.subplots(2, 1, sharex=True, figsize=(8, 7.6), height_ratios=[3, 1.4], layout="constrained")
    inertia, delta = sizing.candidates, sizing.candidate_irregularity
    shown = np.isfinite(delta) & (inertia > 0)
    span = np.geomspace(inertia[shown].min() / 1.5, inertia[shown].max() * 1.5, 300)
    ax.plot(span, sizing.irregularity_tredgold(span), color=_RESISTING, lw=1.6,
            label="Tredgold: dE_max / ((I_machine + I_f r^2) w_m^2)")
    ax.plot(inertia[shown], delta[shown], "o", color=_DRIVING, ms=4, label="simulated (each point a run)")
    ax.axhline(sizing.irregularity, color="0.3", lw=0.9, ls=":", label=f"target delta = {sizing.irregularity:g}")
    ax.axvline(sizing.flywheel_inertia_tredgold, color=_RESISTING, lw=0.9, ls="--",
               label=f"Tredgold's flywheel {sizing.flywheel_inertia_tredgold:.6g} kg*m^2 "
                     f"(simulated delta {sizing.irregularity_with_tredgold_flywheel:.5g})")
    ax.axvline(sizing.flywheel_inertia, color=_DRIVING, lw=0.9, ls="-.",
               label=f"simulation meets the target: {sizing.flywheel_inertia:.6g} kg*m^2")
    gap = 100 * (delta[shown] / sizing.irregularity_tredgold(inertia[shown]) - 1)
    ax_gap.plot(inertia[shown], gap, "o-", color=_DRIVING, ms=3, lw=1.0)
    ax_gap.axhline(0.0, color="k", lw=0.6)
    ax_gap.set_ylabel("simulated / Tredgold - 1 [%]")
    for axis in (ax, ax_gap):
        axis.set_xscale("log")
        axis.grid(True, which="both", lw=0.4, alpha=0.5)
        axis.xaxis.set_major_formatter(ScalarFormatter())
        axis.xaxis.set_minor_formatter(ScalarFormatter())
    ax.set_yscale("log")
    ax.yaxis.set_major_formatter(ScalarFormatter())
    ax.yaxis.set_minor_formatter(ScalarFormatter())
    ax_gap.set_xlabel(f"flywheel inertia on the {sizing.shaft} shaft [kg*m^2]")
    ax.set_ylabel("degree of irregularity delta")
    ax.set_title(f"{title}: delta against flywheel inertia (w_m = {sizing.mean_speed * RPM:.5g} rpm)",
                 fontsize=11, loc="left")
    # below the panels, where it hides no point and no line
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncols=2, fontsize=8, frameon=False)
    fig.savefig(output, dpi=150)
    plt.close(fig)

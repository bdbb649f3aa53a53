"""Figures of a results file: speeds, clutch slip and clutch torque against time.

matplotlib is imported here only, so the rest of hoistsim never pays for it.
"""

from __future__ import annotations

import math

import numpy as np

from .output import read_runs

RPM = 30.0 / math.pi  # rad/s -> rpm
_EVENT_STYLE = {"lock": ("#1b7837", "-"), "unlock": ("#b2182b", "--"), "reversal": ("#762a83", ":"),
                "brake_release": ("#444444", "-."), "engage": ("#2166ac", ":"), "disengage": ("#2166ac", ":")}


def plot_file(path, output) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    runs = read_runs(path)
    fig = speed_and_slip_figure(runs, plt)
    fig.savefig(output, dpi=150, bbox_inches="tight")
    plt.close(fig)


def _colours(count, plt):
    if count == 1:
        return ["#1f4e79"]
    cmap = plt.get_cmap("viridis")
    return [cmap(x) for x in np.linspace(0.0, 0.9, count)]


def speed_and_slip_figure(runs, plt):
    fig, (ax_speed, ax_slip, ax_torque) = plt.subplots(
        3, 1, sharex=True, figsize=(9, 9), gridspec_kw={"height_ratios": [3, 2, 2]})
    colours = _colours(len(runs), plt)
    for run, colour in zip(runs, colours):
        attrs = run["attrs"]
        label = str(attrs.get("label", attrs.get("name", "")))
        t = run["time"]
        ratio = json_ratio(attrs)
        ax_speed.plot(t, run["motor_speed"] * RPM, color=colour, lw=1.6, label=f"{label}: motor")
        ax_speed.plot(t, run["drum_speed"] * ratio * RPM, color=colour, lw=1.6, ls="--",
                      label=f"{label}: clutch output")
        ax_slip.plot(t, run["slip_speed"] * RPM, color=colour, lw=1.4, label=label)
        ax_torque.plot(t, run["clutch_torque"], color=colour, lw=1.4, label=f"{label}: transmitted")
        ax_torque.plot(t, run["clutch_capacity"], color=colour, lw=1.0, ls=":", label=f"{label}: static capacity")
        locked = run["clutch_locked"].astype(bool)
        if len(runs) == 1 and locked.any():
            ax_slip.fill_between(t, 0, 1, where=locked, transform=ax_slip.get_xaxis_transform(),
                                 color="#1b7837", alpha=0.08, lw=0, label="locked")
        _mark_events(run["events"], (ax_speed, ax_slip, ax_torque), colour if len(runs) > 1 else None)

    ax_speed.set_ylabel("shaft speed [rpm]")
    ax_speed.set_title(_title(runs), fontsize=11, loc="left")
    drum_axis = ax_speed.secondary_yaxis(
        "right", functions=(lambda x, r=json_ratio(runs[0]["attrs"]): x / r,
                            lambda x, r=json_ratio(runs[0]["attrs"]): x * r))
    drum_axis.set_ylabel("drum speed [rpm]  (clutch output / gear ratio)")
    ax_slip.axhline(0.0, color="k", lw=0.6)
    ax_slip.set_ylabel("clutch slip speed [rpm]\n(motor - clutch output)")
    ax_torque.set_ylabel("clutch torque [N*m]")
    ax_torque.set_xlabel("time [s]")
    for ax in (ax_speed, ax_slip, ax_torque):
        ax.grid(True, lw=0.4, alpha=0.6)
        ax.set_xlim(min(r["time"][0] for r in runs), max(r["time"][-1] for r in runs))
    legend_cols = 1 if len(runs) <= 2 else 2
    ax_speed.legend(fontsize=8, ncol=legend_cols, loc="lower right")
    ax_slip.legend(fontsize=8, ncol=legend_cols, loc="upper right")
    ax_torque.legend(fontsize=8, ncol=legend_cols, loc="lower right")
    fig.align_ylabels()
    fig.tight_layout()
    return fig


def json_ratio(attrs) -> float:
    import json

    gears = json.loads(attrs["parameters"])["gears"]
    return gears["wheel_teeth"] / gears["pinion_teeth"]


def _title(runs) -> str:
    name = str(runs[0]["attrs"].get("name", ""))
    if len(runs) == 1:
        s = runs[0]["attrs"]
        lock = s.get("lockup_time", float("nan"))
        lock_text = "never locks" if math.isnan(lock) else f"locks at {lock:.3f} s"
        return f"{name}: {lock_text}, clutch heat {s.get('slip_energy', 0.0) / 1000:.2f} kJ"
    return f"{name}: {len(runs)} runs"


def _mark_events(events, axes, colour) -> None:
    for row in events:
        kind = row["kind"].decode() if isinstance(row["kind"], bytes) else str(row["kind"])
        default_colour, style = _EVENT_STYLE.get(kind, ("#888888", ":"))
        for ax in axes:
            ax.axvline(float(row["time"]), color=colour or default_colour, ls=style, lw=0.8, alpha=0.7)
        axes[0].annotate(kind.replace("_", " "), (float(row["time"]), 1.0), xycoords=("data", "axes fraction"),
                         xytext=(2, -10), textcoords="offset points", fontsize=7, rotation=90,
                         va="top", color=colour or default_colour)

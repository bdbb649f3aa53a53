"""Figures of a results file: speeds, clutch slip and clutch torque against time.

matplotlib is imported here only, so the rest of hoistsim never pays for it.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .output import read_runs, read_summary

RPM = 30.0 / math.pi  # rad/s -> rpm
_EVENT_STYLE = {"lock": ("#1b7837", "-"), "unlock": ("#b2182b", "--"), "reversal": ("#762a83", ":"),
                "brake_release": ("#444444", "-."), "engage": ("#2166ac", ":"), "disengage": ("#2166ac", ":")}


def plot_file(path, output) -> list[str]:
    """Write the figures of a results file; returns the paths written."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    output = Path(output)
    runs = read_runs(path)
    summaries = read_summary(path)
    swept = _swept(path, summaries)
    written = []
    if runs:
        fig = speed_and_slip_figure(runs, plt, swept)
        fig.savefig(output, dpi=150, bbox_inches="tight")
        plt.close(fig)
        written.append(str(output))
    periodic = [run for run in runs if "turning_moment" in run]
    if periodic:  # the first run's periodic regime: its turning-moment diagram and speed over a period
        from .plotting_periodic import periodic_figure

        target = output.with_name(output.stem + "_periodic" + output.suffix)
        fig = periodic_figure(periodic[0], plt)
        fig.savefig(target, dpi=150, bbox_inches="tight")
        plt.close(fig)
        written.append(str(target))
    if len(summaries) > 1 or not runs:
        target = output.with_name(output.stem + "_summary" + output.suffix) if runs else output
        fig = summary_figure(summaries, swept, plt)
        fig.savefig(target, dpi=150, bbox_inches="tight")
        plt.close(fig)
        written.append(str(target))
    return written


def _swept(path, summaries):
    """(name, unit scale, unit, values) of the first swept key with numbers, else the run index."""
    import h5py

    with h5py.File(path, "r") as f:
        keys = json.loads(f["summary"].attrs.get("swept_keys", "[]"))
    for key in keys:
        values = np.asarray([row[key] for row in summaries], dtype=float)
        if np.all(np.isfinite(values)):
            scale, unit = _DISPLAY_UNITS.get(key.rsplit(".", 1)[-1], (1.0, "SI"))
            return key, values * scale, unit
    return "run", np.arange(len(summaries), dtype=float), ""


# how a swept key is shown: SI value x scale, in unit
_DISPLAY_UNITS = {
    "engagement_force": (1.0, "N"), "mass": (1.0, "kg"), "release_time": (1.0, "s"),
    "motor_speed": (RPM, "rpm"), "drum_speed": (RPM, "rpm"), "no_load_speed": (RPM, "rpm"),
    "stall_torque": (1.0, "N*m"), "static_friction": (1.0, "-"), "kinetic_friction": (1.0, "-"),
    "half_angle": (180.0 / math.pi, "deg"), "duration": (1.0, "s"),
}


def _colours(count, plt, values=None):
    if count == 1:
        return ["#1f4e79"], None
    cmap = plt.get_cmap("viridis")
    values = np.arange(count, dtype=float) if values is None else np.asarray(values, dtype=float)
    span = (values.min(), values.max()) if values.max() > values.min() else (values.min() - 1, values.max() + 1)
    norm = plt.Normalize(*span)
    return [cmap(0.9 * norm(v)) for v in values], (cmap, norm)


def speed_and_slip_figure(runs, plt, swept=("run", None, "")):
    fig, (ax_speed, ax_slip, ax_torque) = plt.subplots(
        3, 1, sharex=True, figsize=(9, 9), gridspec_kw={"height_ratios": [3, 2, 2]})
    key, values, unit = swept
    colours, scale = _colours(len(runs), plt, values)
    many = len(runs) > 4  # a colour bar instead of one legend entry per run
    for run, colour in zip(runs, colours):
        attrs = run["attrs"]
        label = str(attrs.get("label", attrs.get("name", "")))
        t = run["time"]
        ratio = json_ratio(attrs)
        if many:
            label = None
        ax_speed.plot(t, run["motor_speed"] * RPM, color=colour, lw=1.2 if many else 1.6,
                      label=label and f"{label}: motor")
        ax_speed.plot(t, run["drum_speed"] * ratio * RPM, color=colour, lw=1.2 if many else 1.6, ls="--",
                      label=label and f"{label}: clutch output")
        ax_slip.plot(t, run["slip_speed"] * RPM, color=colour, lw=1.4, label=label)
        ax_torque.plot(t, run["clutch_torque"], color=colour, lw=1.4, label=label and f"{label}: transmitted")
        if not many:
            ax_torque.plot(t, run["clutch_capacity"], color=colour, lw=1.0, ls=":",
                           label=f"{label}: static capacity")
        locked = run["clutch_locked"].astype(bool)
        if len(runs) == 1 and locked.any():
            ax_slip.fill_between(t, 0, 1, where=locked, transform=ax_slip.get_xaxis_transform(),
                                 color="#1b7837", alpha=0.08, lw=0, label="locked")
        _mark_events(run["events"], (ax_speed, ax_slip, ax_torque), colour if len(runs) > 1 else None,
                     named=len(runs) <= 2)

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
    if many:
        ax_speed.plot([], [], color="0.3", lw=1.2, label="motor")
        ax_speed.plot([], [], color="0.3", lw=1.2, ls="--", label="clutch output")
        ax_speed.legend(fontsize=8, loc="lower right")
        fig.tight_layout()
        bar = fig.colorbar(plt.cm.ScalarMappable(norm=scale[1], cmap=scale[0]),
                           ax=[ax_speed, ax_slip, ax_torque], shrink=0.6, pad=0.09)
        bar.set_label(f"{key} [{unit}]" if unit else key)
    else:
        legend_cols = 1 if len(runs) <= 2 else 2
        ax_speed.legend(fontsize=8, ncol=legend_cols, loc="lower right")
        ax_slip.legend(fontsize=8, ncol=legend_cols, loc="upper right")
        ax_torque.legend(fontsize=8, ncol=legend_cols, loc="lower right")
        fig.tight_layout()
    fig.align_ylabels()
    return fig


def summary_figure(summaries, swept, plt):
    """What the designer compares: lock-up time, clutch heat, peak torque, lowest load vs the swept value."""
    key, x, unit = swept
    panels = [("lockup_time", "lock-up time [s]", 1.0), ("slip_energy", "clutch heat [kJ]", 1e-3),
              ("peak_clutch_torque", "peak clutch torque [N*m]", 1.0),
              ("lowest_load_position", "lowest load position [m]", 1.0)]
    fig, axes = plt.subplots(2, 2, sharex=True, figsize=(10, 6.5))
    many = len(summaries) > 60
    for ax, (name, ylabel, scale) in zip(axes.flat, panels):
        y = np.asarray([row[name] for row in summaries], dtype=float) * scale
        ax.plot(x, y, color="#1f4e79", lw=1.5, marker=None if many else "o", ms=4)
        if name == "lockup_time" and np.any(np.isnan(y)):
            never = x[np.isnan(y)]
            ax.plot(never, np.zeros_like(never), "x", color="#b2182b", ms=4 if many else 6,
                    label="never locks")
            ax.legend(fontsize=8)
        if name == "lowest_load_position":
            ax.axhline(0.0, color="k", lw=0.6)
        ax.set_ylabel(ylabel)
        ax.grid(True, lw=0.4, alpha=0.6)
    for ax in axes[1]:
        ax.set_xlabel(f"{key} [{unit}]" if unit else key)
    name = str(summaries[0]["label"]).split("=")[0] if key != "run" else "runs"
    fig.suptitle(f"{len(summaries)} runs: the summary against {name}", fontsize=11, x=0.01, ha="left")
    fig.tight_layout()
    return fig


def json_ratio(attrs) -> float:
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


def _mark_events(events, axes, colour, named: bool = True) -> None:
    for row in events:
        kind = row["kind"].decode() if isinstance(row["kind"], bytes) else str(row["kind"])
        default_colour, style = _EVENT_STYLE.get(kind, ("#888888", ":"))
        for ax in axes:
            ax.axvline(float(row["time"]), color=colour or default_colour, ls=style, lw=0.8, alpha=0.7)
        if not named:  # with many runs the names would pile up; the lines say enough
            continue
        axes[0].annotate(kind.replace("_", " "), (float(row["time"]), 1.0), xycoords=("data", "axes fraction"),
                         xytext=(2, -10), textcoords="offset points", fontsize=7, rotation=90,
                         va="top", color=colour or default_colour)

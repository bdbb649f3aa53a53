"""A fit to a measured trace: each matched series measured against fitted, and its residual under it."""

from __future__ import annotations

import numpy as np

_MEASURED, _FITTED, _START = "0.35", "#c0392b", "#7f8c8d"


def fit_figure(result, output, title: str = "", kind: str | None = None) -> None:
    """``result`` (a :class:`hoistsim.studies.fit.FitResult`) drawn to ``output``: a column of panel pairs, one a
    matched series (measured points, the run at the starting values, the fitted run) over its residual, each
    series in the unit the trace writes it in; ``kind``: png, svg or pdf (default: the name's)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(result.fitted)
    heights = [3, 1.2] * len(names)
    fig, axes = plt.subplots(2 * len(names), 1, sharex=True, figsize=(8.5, 2.6 + 3.4 * len(names)),
                             height_ratios=heights, layout="constrained")
    trace = result.trace
    for k, name in enumerate(names):
        ax, ax_residual = axes[2 * k], axes[2 * k + 1]
        unit = trace.written[name]
        measured = trace.shown(name, trace.columns[name])
        fitted = trace.shown(name, result.fitted[name])
        ax.plot(trace.time, measured, "o", ms=2.2, color=_MEASURED, label="measured")
        if name in result.at_start:
            ax.plot(trace.time, trace.shown(name, result.at_start[name]), color=_START, lw=1.0, ls="--",
                    label="run at the starting values")
        ax.plot(trace.time, fitted, color=_FITTED, lw=1.4, label="fitted run")
        ax.set_ylabel(f"{name} [{unit}]")
        ax.legend(loc="best", fontsize=8, frameon=False)
        residual = measured - fitted
        ax_residual.plot(trace.time, residual, "o", ms=1.8, color=_MEASURED)
        ax_residual.axhline(0.0, color="k", lw=0.6)
        rms = float(np.sqrt(np.mean(residual ** 2)))
        ax_residual.set_ylabel(f"residual [{unit}]")
        ax_residual.text(0.01, 0.95, f"RMS {rms:.3g} {unit}", transform=ax_residual.transAxes, va="top",
                         fontsize=8)
        for axis in (ax, ax_residual):
            axis.grid(True, lw=0.4, alpha=0.5)
    axes[-1].set_xlabel("time [s]")
    fitted_keys = "\n".join(
        f"{key} = {result.values[key]:.5g} ± {result.standard_errors[key]:.2g}"
        + ("" if result.key_units[key] == "1" else f" {result.key_units[key]}")
        + f" (from {result.start[key]:.5g})" for key in result.keys)
    axes[0].set_title(f"{title}: fitted to {_file_name(trace.source)} (± one standard error)\n{fitted_keys}",
                      fontsize=10, loc="left")
    fig.savefig(output, dpi=150, format=kind)
    plt.close(fig)


def _file_name(source: str) -> str:
    return source.replace("\\", "/").rsplit("/", 1)[-1]

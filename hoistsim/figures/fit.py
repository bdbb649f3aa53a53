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
                    label="run at the scenario's values")
        ax.plot(trace.time, fitted, color=_FITTED, lw=1.4, label="fitted run")
        ax.set_ylabel(f"{name} [{unit}]")
        ax.legend(loc="best", fontsize=8, frameon=False)
        residual = measured - fitted
        ax_residual.plot(trace.time, residual, "o", ms=1.8, color=_MEASURED)
        ax_residual.axhline(0.0, color="k", lw=0.6)
        rms = float(np.sqrt(np.mean(residual ** 2)))
        ax_residual.set_ylabel(f"residual [{unit}]")
        ax_residual.text(0.01, 0.95, f"RMS {rms:.3g} {unit}" + _against_noise(result, name),
                         transform=ax_residual.transAxes, va="top", fontsize=8,
                         bbox=dict(facecolor="white", edgecolor="none", alpha=0.85, pad=1.5))
        for axis in (ax, ax_residual):
            axis.grid(True, lw=0.4, alpha=0.5)
    axes[-1].set_xlabel("time [s]")
    fitted_keys = "\n".join(_key_line(result, key) for key in result.keys)
    axes[0].set_title(f"{title}: fitted to {_file_name(trace.source)} (± one standard error)\n{fitted_keys}",
                      fontsize=10, loc="left")
    fig.savefig(output, dpi=150, format=kind)
    plt.close(fig)


def _file_name(source: str) -> str:
    return source.replace("\\", "/").rsplit("/", 1)[-1]


def _key_line(result, key: str) -> str:
    """``key = value ± error unit (where it started)``; a key the trace does not determine says so instead of an error."""
    unit = "" if result.key_units[key] == "1" else f" {result.key_units[key]}"
    error = result.standard_errors[key]
    told = f"{result.values[key]:.5g}{unit}, undetermined" if error is None else \
        f"{result.values[key]:.5g} ± {error:.2g}{unit}"
    given = result.given.get(key, result.start[key])
    # the dashed run is the scenario's values; where the sweep chose another start, say both
    began = (f"scenario {given:.5g}, swept start {result.start[key]:.5g}" if result.start[key] != given
             else f"from {given:.5g}")
    return f"{key} = {told} ({began})"


def _against_noise(result, name: str) -> str:
    """What the residuals say against the noise, where they are not it: the fit does not explain the trace."""
    check = result.checks.get(name)
    if check is None or not (check.far_from_noise or check.patterned):
        return ""
    said = [f"{check.rms / check.noise:.0f} times the noise" if check.far_from_noise and check.noise > 0 else "",
            "patterned" if check.patterned else ""]
    return ": " + ", ".join(word for word in said if word) + " (not a sound fit)"

"""A drawn drivetrain's DC machines: each one's armature current and voltage, and the torque it puts on its
shaft (its air gap's), beside the external torques."""

from __future__ import annotations

from .panel import Display, Panel, Trace


def _panels_for(run: dict) -> tuple:
    machines = (run.get("parameters", {}).get("drivetrain") or {}).get("dc_machines") or {}
    if not machines:
        return ()
    return (Panel("shaft_torques", "external torque [N*m]", 5,
                  tuple(Trace(f"{name} (air gap)", f"{name}_torque") for name in machines), zero_line=True,
                  height=0.8),
            Panel("machine_currents", "armature\ncurrent [A]", 6,
                  tuple(Trace(name, f"{name}_current") for name in machines), zero_line=True, height=0.8),
            Panel("machine_voltages", "armature\nvoltage [V]", 7,
                  tuple(Trace(name, f"{name}_voltage") for name in machines), height=0.8))


def _headline(summary: dict) -> str | None:
    """Each machine's peak armature current: what its supply and its commutator must carry."""
    peaks = [(key[: -len("_peak_current")], float(value)) for key, value in summary.items()
             if key.endswith("_peak_current")  # not an induction machine's (its headline says its torque too)
             and f"{key[: -len('_peak_current')]}_least_torque" not in summary]
    return "; ".join(f"{name} draws up to {peak:.4g} A" for name, peak in peaks) or None


DC_MACHINE = Display(panels_for=_panels_for, headline=_headline,
                     reads=lambda column: column.endswith(("_current", "_voltage", "_torque")))

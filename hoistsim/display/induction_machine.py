"""A drawn drivetrain's induction machines: each one's stator current (its space phasor's magnitude, a phase
current's amplitude) and winding voltage, and the torque its air gap puts on its shaft, beside the external
torques (panels shared with the DC machines')."""

from __future__ import annotations

from .panel import Display, Panel, Trace


def _panels_for(run: dict) -> tuple:
    machines = (run.get("parameters", {}).get("drivetrain") or {}).get("induction_machines") or {}
    if not machines:
        return ()
    return (Panel("shaft_torques", "external torque [N*m]", 5,
                  tuple(Trace(f"{name} (air gap)", f"{name}_torque") for name in machines), zero_line=True,
                  height=0.8),
            Panel("machine_currents", "stator current\namplitude [A]", 6,
                  tuple(Trace(name, f"{name}_current") for name in machines), zero_line=True, height=0.8),
            Panel("machine_voltages", "winding voltage\namplitude [V]", 7,
                  tuple(Trace(name, f"{name}_voltage") for name in machines), height=0.6))


def _headline(summary: dict) -> str | None:
    """Each machine's torque from its least to its peak (a start's pulsation in the shafts) and its peak
    current."""
    said = []
    for key in summary:
        if key.endswith("_least_torque"):
            name = key[: -len("_least_torque")]
            said.append(f"{name} torque {float(summary[key]):.4g} to {float(summary[f'{name}_peak_torque']):.4g} N*m, "
                        f"current up to {float(summary[f'{name}_peak_current']):.4g} A")
    return "; ".join(said) or None


INDUCTION_MACHINE = Display(panels_for=_panels_for, headline=_headline,
                            reads=lambda column: column.endswith(("_current", "_voltage", "_torque")))

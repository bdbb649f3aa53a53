"""A drawn drivetrain's induction machines: each one's stator current (its space phasor's magnitude, a phase
current's amplitude) and winding voltage, and the torque its air gap puts on its shaft, beside the external
torques (panels shared with the DC machines')."""

from __future__ import annotations

from ._machines import machine_panels, reads_machine_column
from .panel import Display


def _panels_for(run: dict) -> tuple:
    return machine_panels(run, "induction_machines", "stator current\namplitude [A]", "winding voltage\namplitude [V]")


def _headline(summary: dict) -> str | None:
    """Each machine's torque from its least to its peak (a start's pulsation in the shafts) and its peak
    current."""
    said = []
    for key in summary:
        if key.endswith("_min_torque"):
            name = key[: -len("_min_torque")]
            said.append(f"{name} torque {float(summary[key]):.4g} to {float(summary[f'{name}_max_torque']):.4g} N*m, "
                        f"current up to {float(summary[f'{name}_peak_current']):.4g} A")
    return "; ".join(said) or None


INDUCTION_MACHINE = Display(panels_for=_panels_for, headline=_headline, reads=reads_machine_column)

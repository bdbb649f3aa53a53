"""A drawn drivetrain's DC machines: each one's armature current and voltage, and the torque it puts on its
shaft (its air gap's), beside the external torques."""

from __future__ import annotations

from ._machines import machine_panels, reads_machine_column
from .panel import Display


def _panels_for(run: dict) -> tuple:
    return machine_panels(run, "dc_machines", "armature\ncurrent [A]", "armature\nvoltage [V]")


def _headline(summary: dict) -> str | None:
    """Each machine's peak armature current: what its supply and its commutator must carry."""
    peaks = [(key[: -len("_peak_current")], float(value)) for key, value in summary.items()
             if key.endswith("_peak_current")  # not an induction machine's (its headline says its torque too)
             and f"{key[: -len('_peak_current')]}_min_torque" not in summary]
    return "; ".join(f"{name} draws up to {peak:.4g} A" for name, peak in peaks) or None


DC_MACHINE = Display(panels_for=_panels_for, headline=_headline, reads=reads_machine_column)

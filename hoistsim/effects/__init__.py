"""Optional effects: each YAML section that is present assembles only its own parts.

An effect is an equinox module whose fields are traced inputs.  A scene that
leaves a section out has no instance of its effect, so nothing of it is traced,
compiled, integrated or written.
"""

from __future__ import annotations

from ._base import AbstractEffect as AbstractEffect
from ._base import RowContext as RowContext
from .bearings import DrumShaftLoads as DrumShaftLoads
from .brake import HoldingBrake as HoldingBrake

# YAML section -> effect class, in the order their outputs are written
REGISTRY: dict[str, type[AbstractEffect]] = {
    HoldingBrake.section: HoldingBrake,
    DrumShaftLoads.section: DrumShaftLoads,
}


def effects_for(scenario) -> tuple[AbstractEffect, ...]:
    """The effects a scenario names, built from their sections."""
    built = []
    for section, cls in REGISTRY.items():
        spec = getattr(scenario, section, None)
        if spec is not None:
            built.append(cls.from_spec(spec, scenario))
    return tuple(built)

"""A drawn drivetrain's eddy-current brakes and the heat capacitors they warm: the power each brakes away, the
temperature each capacitor reaches."""

from __future__ import annotations

from .panel import Display, Panel, Trace

ZERO_CELSIUS = 273.15  # K


def _panels_for(run: dict) -> tuple:
    drawn = run.get("parameters", {}).get("drivetrain") or {}
    brakes, capacitors = drawn.get("eddy_current_brakes") or {}, drawn.get("heat_capacitors") or {}
    panels = []
    if brakes:
        panels.append(Panel("eddy_current_power", "eddy-current brake\nloss power [kW]", 30,
                            tuple(Trace(name, f"{name}_loss_power") for name in brakes), scale=1e-3, height=0.8))
    if capacitors:
        panels.append(Panel("capacitor_temperature", "heat capacitor\ntemperature [degC]", 31, tuple(
            Trace(name, f"{name}_temperature", value=lambda run, name=name: run[f"{name}_temperature"] - ZERO_CELSIUS)
            for name in capacitors), height=0.8))
    return tuple(panels)


EDDY_CURRENT_BRAKE = Display(panels_for=_panels_for,
                             reads=lambda column: column.endswith(("_loss_power", "_temperature")))

"""The cone clutch's friction surfaces as one lump of heat: their temperature, cooling and overheating."""

from __future__ import annotations

from typing import ClassVar

import numpy as np

from ..._pytree import static
from ..core.element import AbstractElement
from ._slip_heat import slip_power

class ClutchHeating(AbstractElement):
    """C dT/dt = P - G (T - T_ambient): the clutch's heat of slip P (its torque times the slip speed)
    warms a lumped heat capacity C that a conductance G cools towards ambient.

    The temperature is a state; so is the heat passed to ambient, so that the heat
    stored, C (T - T_0), and the heat passed on account for the heat of slip
    exactly (a ledger of their own, beside the energy ledger in which the slip is
    a loss).  Where the clutch's friction depends on the temperature
    (``clutch_heating.static_friction`` / ``kinetic_friction``) the cone clutch
    reads this state.  ``max_temperature``: an ``overheat`` row where the
    temperature rises through it, located exactly even where it coincides with
    another event; the peak temperature is a row of its own
    (``temperature_peak``), so the summary's peak is exact.
    """

    heat_capacity: object  # C, J/K
    conductance: object  # G, W/K
    ambient_temperature: object  # K
    initial_temperature: object  # K
    max_temperature: object  # K (inf where no limit is given)
    limited: bool = static(False)  # a max_temperature is given: the overheat guard and summary exist

    section: ClassVar[str] = "clutch_heating"
    observation_kinds: ClassVar[tuple] = ("temperature_peak", "overheat")
    limits: ClassVar[tuple] = ("overheat",)  # recorded even where it coincides with another event (a lock)
    ledger_kinds: ClassVar[dict] = {"clutch_heat_stored": "heat of clutch_energy",
                                    "clutch_heat_to_ambient": "heat of clutch_energy"}
    columns: ClassVar[dict] = {
        "clutch_temperature": ("K", "temperature of the clutch's friction surfaces (one lump)"),
        "clutch_cooling_power": ("W", "heat the clutch passes to ambient, G (T - T_ambient)"),
        "clutch_heat_to_ambient": ("J", "heat the clutch has passed to ambient so far"),
    }

    @property
    def summaries(self) -> dict:
        peak = {"peak_clutch_temperature": "K", "final_clutch_temperature": "K"}
        return {**peak, "overheat_time": "s"} if self.limited else peak

    def observes(self, kind: str) -> bool:
        return kind != "overheat" or self.limited

    @classmethod
    def from_spec(cls, spec, scenario) -> "ClutchHeating":
        limited = spec.max_temperature is not None
        return cls(heat_capacity=spec.heat_capacity, conductance=spec.cooling,
                   ambient_temperature=spec.ambient_temperature, initial_temperature=spec.start_temperature,
                   max_temperature=spec.max_temperature if limited else np.inf, limited=limited)

    def cooling_power(self, x):
        return self.conductance * (x.state("clutch_temperature") - self.ambient_temperature)

    def states(self) -> dict:
        return {"clutch_temperature": self.initial_temperature, "clutch_heat_to_ambient": 0.0}

    def rates(self, x) -> dict:
        cooling = self.cooling_power(x)
        return {"clutch_temperature": (slip_power(x, "clutch") - cooling) / self.heat_capacity,
                "clutch_heat_to_ambient": cooling}

    def ledger(self, x) -> dict:
        stored = self.heat_capacity * (x.state("clutch_temperature") - self.initial_temperature)
        return {"clutch_heat_stored": stored, "clutch_heat_to_ambient": x.state("clutch_heat_to_ambient")}

    def observations(self, x) -> dict:
        # the temperature's rate falls through zero at its peak (a row, so the summary's peak is exact);
        # the limit less the temperature falls through zero where it overheats
        seen = {"temperature_peak": self.rates(x)["clutch_temperature"]}
        if self.limited:
            seen["overheat"] = self.max_temperature - x.state("clutch_temperature")
        return seen

    def extremes(self, x) -> dict:
        temperature = x.state("clutch_temperature")
        out = {"peak_clutch_temperature": ("max", temperature)}
        if self.limited:
            # an overheat row is recorded only where the temperature has reached the limit (its guard <= 0)
            out["overheat_time"] = ("first", temperature >= self.max_temperature)
        return out

    def summary(self, x) -> dict:
        return {"final_clutch_temperature": x.state("clutch_temperature")}

    def outputs(self, x) -> dict:
        return {"clutch_temperature": x.state("clutch_temperature"), "clutch_cooling_power": self.cooling_power(x),
                "clutch_heat_to_ambient": x.state("clutch_heat_to_ambient")}

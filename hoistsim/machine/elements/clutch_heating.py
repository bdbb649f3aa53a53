"""A friction clutch's faces as one lump of heat: their temperature, cooling and overheating."""

from __future__ import annotations

import numpy as np

from ..._pytree import static
from ..core.element import AbstractElement
from ._names import NamedOutputs
from ._slip_heat import slip_power


class ClutchHeating(NamedOutputs, AbstractElement):
    """C dT/dt = P - G (T - T_ambient): a clutch's heat of slip P (its torque times the slip speed)
    warms a lumped heat capacity C that a conductance G cools towards ambient (a clutch's ``heating``;
    the hoist's ``clutch_heating``).

    The temperature is a state (``<clutch>_temperature``); so is the heat passed to ambient, so that the
    heat stored, C (T - T_0), and the heat passed on account for the heat of slip exactly (a ledger of
    their own, beside the energy ledger in which the slip is a loss).  Where the clutch's friction depends
    on the temperature (the heating's ``static_friction`` / ``kinetic_friction`` tables) the clutch reads
    this state.  ``max_temperature``: an overheat row where the temperature rises through it, located
    exactly even where it coincides with another event; the peak temperature is a row of its own, so the
    summary's peak is exact.
    """

    heat_capacity: object  # C, J/K
    conductance: object  # G, W/K
    ambient_temperature: object  # K
    initial_temperature: object  # K
    max_temperature: object  # K (inf where no limit is given)
    limited: bool = static(False)  # a max_temperature is given: the overheat guard and summary exist
    clutch: str = static("")  # the clutch's name

    @classmethod
    def from_spec(cls, spec) -> "ClutchHeating":
        heating = spec.heating
        limited = heating.max_temperature is not None
        return cls(heat_capacity=heating.heat_capacity, conductance=heating.cooling,
                   ambient_temperature=heating.ambient_temperature, initial_temperature=heating.start_temperature,
                   max_temperature=heating.max_temperature if limited else np.inf, limited=limited,
                   clutch=spec.name)

    @property
    def section(self) -> str:  # a name of its own: its guards are found by it
        return f"{self.clutch}_heating"

    @property
    def part_name(self) -> str:
        return self.clutch

    @property
    def temperature(self) -> str:
        return self.named("{name}_temperature")

    @property
    def to_ambient(self) -> str:
        return self.named("{name}_heat_to_ambient")

    @property
    def observation_kinds(self) -> tuple:
        return (self.named("{name}_temperature_peak"), self.named("{name}_overheat"))

    @property
    def limits(self) -> tuple:  # recorded even where it coincides with another event (a lock)
        return (self.named("{name}_overheat"),)

    @property
    def ledger_kinds(self) -> dict:
        heat_of = f"heat of {self.clutch}_energy"
        return {self.named("{name}_heat_stored"): heat_of, self.to_ambient: heat_of}

    @property
    def columns(self) -> dict:
        return {
            self.temperature: ("K", f"temperature of {self.clutch}'s friction surfaces (one lump)"),
            self.named("{name}_cooling_power"): ("W", f"heat {self.clutch} passes to ambient, "
                                                      "G (T - T_ambient)"),
            self.to_ambient: ("J", f"heat {self.clutch} has passed to ambient so far"),
        }

    @property
    def summaries(self) -> dict:
        peak = {self.named("peak_{name}_temperature"): "K", self.named("final_{name}_temperature"): "K"}
        return {**peak, self.named("{name}_overheat_time"): "s"} if self.limited else peak

    def observes(self, kind: str) -> bool:
        return kind != self.named("{name}_overheat") or self.limited

    def cooling_power(self, x):
        return self.conductance * (x.state(self.temperature) - self.ambient_temperature)

    def states(self) -> dict:
        return {self.temperature: self.initial_temperature, self.to_ambient: 0.0}

    def rates(self, x) -> dict:
        cooling = self.cooling_power(x)
        return {self.temperature: (slip_power(x, self.clutch) - cooling) / self.heat_capacity,
                self.to_ambient: cooling}

    def ledger(self, x) -> dict:
        stored = self.heat_capacity * (x.state(self.temperature) - self.initial_temperature)
        return {self.named("{name}_heat_stored"): stored, self.to_ambient: x.state(self.to_ambient)}

    def observations(self, x) -> dict:
        # the temperature's rate falls through zero at its peak (a row, so the summary's peak is exact);
        # the limit less the temperature falls through zero where it overheats
        seen = {self.named("{name}_temperature_peak"): self.rates(x)[self.temperature]}
        if self.limited:
            seen[self.named("{name}_overheat")] = self.max_temperature - x.state(self.temperature)
        return seen

    def extremes(self, x) -> dict:
        temperature = x.state(self.temperature)
        out = {self.named("peak_{name}_temperature"): ("max", temperature)}
        if self.limited:
            # an overheat row is recorded only where the temperature has reached the limit (its guard <= 0)
            out[self.named("{name}_overheat_time")] = ("first", temperature >= self.max_temperature)
        return out

    def summary(self, x) -> dict:
        return {self.named("final_{name}_temperature"): x.state(self.temperature)}

    def outputs(self, x) -> dict:
        return {self.temperature: x.state(self.temperature), self.named("{name}_cooling_power"): self.cooling_power(x),
                self.to_ambient: x.state(self.to_ambient)}

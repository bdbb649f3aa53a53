"""A lumped heat capacity warmed by a part's heat (Modelica's HeatCapacitor): an eddy-current brake's."""

from __future__ import annotations

from ..._pytree import static
from ..core.element import AbstractElement
from .eddy_current_brake import EddyCurrentBrake


class HeatCapacitor(AbstractElement):
    """C dT/dt = P: the heat P of the eddy-current brake that names it (``heat_to``) warms a heat capacity C,
    nothing cooling it (Modelica's HeatCapacitor on the brake's heat port).  The temperature is the state
    ``<name>_temperature``, which the brake reads; the heat stored, C (T - T_0), is where the brake's heat went
    (a ledger of its own, against the brake's loss).

    It holds the brake (its numbers, built from the brake's section) to work out the heat flowing in.
    """

    heat_capacity: object  # C, J/K
    initial_temperature: object  # T_0, K
    brake: EddyCurrentBrake  # the part whose heat warms it
    section: str = static("")  # its key in drivetrain.heat_capacitors

    @classmethod
    def from_spec(cls, spec) -> "HeatCapacitor":
        return cls(heat_capacity=spec.heat_capacity, initial_temperature=spec.temperature,
                   brake=EddyCurrentBrake.from_spec(spec.resolved("brake")), section=spec.name)

    @property
    def temperature(self) -> str:
        return f"{self.section}_temperature"

    @property
    def heat_stored(self) -> str:
        return f"{self.section}_heat_stored"

    @property
    def ledger_kinds(self) -> dict:
        return {self.heat_stored: f"heat of {self.brake.heat_state}"}

    @property
    def columns(self) -> dict:
        return {self.temperature: ("K", f"temperature of heat capacitor {self.section}"),
                self.heat_stored: ("J", f"heat stored in heat capacitor {self.section}, C (T - T_0)")}

    @property
    def summaries(self) -> dict:
        return {f"final_{self.temperature}": "K"}

    def states(self) -> dict:
        return {self.temperature: self.initial_temperature}

    def rates(self, x) -> dict:
        return {self.temperature: self.brake.loss_power(x) / self.heat_capacity}

    def stored(self, x):
        return self.heat_capacity * (x.state(self.temperature) - self.initial_temperature)

    def ledger(self, x) -> dict:
        return {self.heat_stored: self.stored(x)}

    def summary(self, x) -> dict:
        return {f"final_{self.temperature}": x.state(self.temperature)}

    def outputs(self, x) -> dict:
        return {self.temperature: x.state(self.temperature), self.heat_stored: self.stored(x)}

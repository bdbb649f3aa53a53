"""An eddy-current brake on a shaft of a drawn drivetrain (Modelica's EddyCurrentTorque)."""

from __future__ import annotations

from ..._pytree import static
from ..core.element import AbstractElement
from ._signal import signal_at, signal_fields, signal_tables

_ALPHA_TEMPERATURE = 293.15  # K: the temperature coefficient is given at 20 degC (Modelica's alpha20)


class EddyCurrentBrake(AbstractElement):
    """A torque braking its shaft, 2 tau_n e^2 w_n / (1 + w_n^2) against its turning, w_n = w / (w_nom (1 + alpha
    (T - T_ref))): greatest, tau_n e^2, at w_nom times the disc's resistance over its resistance at T_ref, which
    grows with its temperature T (alpha: the coefficient at 20 degC brought to T_ref, Modelica's convertAlpha).
    e is the excitation, a signal of time.  T is the temperature of the heat capacitor its heat goes into
    (``heat_to``; that capacitor reads ``loss_power``), or a constant.

    Its heat, the braking torque times the speed, is the state ``<name>_heat`` and a loss of the energy ledger.
    """

    nominal_torque: object  # tau_n, N*m
    nominal_speed: object  # w_nom, rad/s, at the reference temperature
    excitation_times: object  # s
    excitation_values: object  # 1
    excitation_amplitudes: object
    excitation_frequencies: object  # Hz
    excitation_phases: object  # rad
    temperature_coefficient: object  # alpha20, 1/K at 20 degC
    reference_temperature: object  # T_ref, K
    temperature: object  # K: T where it heats no capacitor
    excitation_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    excitation_envelope_values: object = None
    on_line: bool = static(False)  # it brakes a mass (Modelica's EddyCurrentForce: N, m/s)
    shaft: str = static("")
    section: str = static("")  # its key in drivetrain.eddy_current_brakes
    heat_to: str | None = static(None)  # the heat capacitor its heat warms, whose temperature it has

    @classmethod
    def from_spec(cls, spec) -> "EddyCurrentBrake":
        fixed = spec.reference_temperature if spec.temperature is None else spec.temperature
        return cls(nominal_torque=spec.nominal_torque, nominal_speed=spec.nominal_speed,
                   **signal_fields(spec.excitation, "excitation"), temperature_coefficient=spec.temperature_coefficient,
                   reference_temperature=spec.reference_temperature, temperature=fixed,
                   on_line=spec.resolved("on_line"), shaft=spec.shaft,
                   section=spec.name, heat_to=spec.heat_to)

    @property
    def heat_state(self) -> str:
        return f"{self.section}_heat"

    @property
    def ledger_kinds(self) -> dict:
        return {self.heat_state: "loss"}

    @property
    def columns(self) -> dict:
        name = self.section
        what, units, body = ("force", "N", "mass") if self.on_line else ("torque", "N*m", "shaft")
        return {f"{name}_{what}": (units, f"{what} eddy-current brake {name} applies to {body} {self.shaft}, "
                                          f"positive in the {body}'s positive sense"),
                f"{name}_loss_power": ("W", f"heat eddy-current brake {name} makes, its braking torque times the "
                                            "speed"),
                f"{name}_heat": ("J", f"heat eddy-current brake {name} has made so far")}

    def tables(self) -> dict:
        return signal_tables(self, "excitation")

    def excitation(self, x):
        return signal_at(self, x, "excitation")

    def braking_torque(self, x):
        """The torque against the turning (N*m): positive braking a shaft turning forwards."""
        temperature = self.temperature if self.heat_to is None else x.state(f"{self.heat_to}_temperature")
        alpha20 = self.temperature_coefficient
        alpha = alpha20 / (1.0 + alpha20 * (self.reference_temperature - _ALPHA_TEMPERATURE))
        w = x.speed(self.shaft) / (self.nominal_speed * (1.0 + alpha * (temperature - self.reference_temperature)))
        return 2.0 * self.nominal_torque * self.excitation(x) ** 2 * w / (1.0 + w * w)

    def loss_power(self, x):
        """W: the heat it makes, its braking torque times the speed (never negative)."""
        return self.braking_torque(x) * x.speed(self.shaft)

    def torques(self, x) -> tuple:
        return ((self.shaft, -self.braking_torque(x)),)

    def states(self) -> dict:
        return {self.heat_state: 0.0}

    def rates(self, x) -> dict:
        return {self.heat_state: self.loss_power(x)}

    def ledger(self, x) -> dict:
        return {self.heat_state: x.state(self.heat_state)}

    def outputs(self, x) -> dict:
        name = self.section
        return {f"{name}_{'force' if self.on_line else 'torque'}": -self.braking_torque(x),
                f"{name}_loss_power": self.loss_power(x),
                f"{name}_heat": x.state(self.heat_state)}

"""A permanent-magnet DC machine on a shaft of a drawn drivetrain (Modelica's DC_PermanentMagnet)."""

from __future__ import annotations

from ..._pytree import static
from ._electrical import AbstractElectricalMachine
from ._signal import signal_at, signal_fields, signal_tables


class DcMachine(AbstractElectricalMachine):
    """Its armature circuit, L di/dt = v - R i - k w, driven by the armature voltage v (a signal of time), and
    its air-gap torque k i on its shaft, k the flux constant (V*s, N*m/A) and w the shaft's speed: a motor where
    k i drives the shaft, a generator where it brakes it.

    The armature current i is a state (``<name>_current``), its peak magnitude a row of its own (an observation,
    so the summary's ``<name>_peak_current`` is exact); so are the electrical energy it takes in (the
    integral of v i: the ledger's work) and its armature's heat (of R i^2: a loss).  The magnetic energy of its
    inductance, L i^2 / 2, is stored (the ledger's potential): v i = R i^2 + d(L i^2 / 2)/dt + k i w, the last
    the air gap's power into the shaft.
    """

    armature_resistance: object  # R, ohm
    armature_inductance: object  # L, H
    flux_constant: object  # k, V*s
    rotor_inertia: object  # kg*m^2, on its shaft
    initial_current: object  # A, at the start
    voltage_times: object  # s
    voltage_values: object  # V
    voltage_amplitudes: object
    voltage_frequencies: object  # Hz
    voltage_phases: object  # rad
    voltage_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    voltage_envelope_values: object = None
    shaft: str = static("")
    section: str = static("")  # its key in drivetrain.dc_machines

    @classmethod
    def from_spec(cls, spec) -> "DcMachine":
        return cls(armature_resistance=spec.armature_resistance, armature_inductance=spec.armature_inductance,
                   flux_constant=spec.flux(), rotor_inertia=spec.rotor_inertia, initial_current=spec.current,
                   **signal_fields(spec.voltage, "voltage"), shaft=spec.shaft, section=spec.name)

    @property
    def current_state(self) -> str:
        return f"{self.section}_current"

    @property
    def columns(self) -> dict:
        name = self.section
        return {f"{name}_current": ("A", f"armature current of DC machine {name}"),
                f"{name}_voltage": ("V", f"armature voltage of DC machine {name}"),
                f"{name}_torque": ("N*m", f"air-gap torque of DC machine {name} on shaft {self.shaft}, positive in "
                                          "the shaft's positive sense"),
                f"{name}_power": ("W", f"electrical power DC machine {name} takes in (negative: gives back)")}

    @property
    def summaries(self) -> dict:
        return {f"{self.section}_peak_current": "A"}

    @property
    def observation_kinds(self) -> tuple:
        return (f"{self.section}_current_peak",)

    def tables(self) -> dict:
        return signal_tables(self, "voltage")

    def voltage(self, x):
        return signal_at(self, x, "voltage")

    def air_gap_torque(self, x):
        """N*m: k i, on its shaft."""
        return self.flux_constant * x.state(self.current_state)

    def inertias(self) -> tuple:
        return ((self.shaft, self.rotor_inertia),)

    def torques(self, x) -> tuple:
        return ((self.shaft, self.air_gap_torque(x)),)

    def states(self) -> dict:
        return {self.current_state: self.initial_current, self.input_state: 0.0, self.copper_state: 0.0}

    def rates(self, x) -> dict:
        current = x.state(self.current_state)
        induced = self.flux_constant * x.speed(self.shaft)
        voltage = self.voltage(x)
        return {self.current_state: (voltage - self.armature_resistance * current - induced)
                / self.armature_inductance,
                self.input_state: voltage * current,
                self.copper_state: self.armature_resistance * current * current}

    def ledger(self, x) -> dict:
        current = x.state(self.current_state)
        return self.electrical_ledger(x, 0.5 * self.armature_inductance * current * current)

    def observations(self, x) -> dict:
        # i di/dt falls through zero where the current's magnitude peaks: a row, so the summary's peak is exact
        current = x.state(self.current_state)
        return {f"{self.section}_current_peak": current * self.rates(x)[self.current_state]}

    def extremes(self, x) -> dict:
        current = x.state(self.current_state)
        return {f"{self.section}_peak_current": ("max", abs(current))}

    def outputs(self, x) -> dict:
        name, current, voltage = self.section, x.state(self.current_state), self.voltage(x)
        return {f"{name}_current": current, f"{name}_voltage": voltage, f"{name}_torque": self.air_gap_torque(x),
                f"{name}_power": voltage * current}

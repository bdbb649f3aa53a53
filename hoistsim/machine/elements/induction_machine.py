"""A squirrel-cage induction machine on a shaft of a drawn drivetrain (Modelica's IM_SquirrelCage)."""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np

from ..._pytree import static
from ._electrical import AbstractElectricalMachine
from ._signal import signal_at, signal_fields, signal_tables

PHASES = 3
HALF_PHASES = PHASES / 2.0  # the amplitude-invariant space phasor's power and torque factor, m / 2
DELTA_LEAD = math.pi / 6.0  # a delta winding's voltage leads a star winding's by 30 degrees
SINE = -math.pi / 2.0  # phase 1's voltage is a sine: its space phasor lags the cosine's by 90 degrees


class InductionMachine(AbstractElectricalMachine):
    """Its space-phasor model in the stator's frame, the stator's and the rotor's flux linkages its states:
    psi_s' = v_s - R_s i_s, psi_r' = -R_r i_r + j p w psi_r (the cage shorted, w the shaft's speed), the currents
    from the fluxes through the inductance matrix [[L_ss + L_m, L_m], [L_m, L_rs + L_m]], and the air-gap torque
    3/2 p Im(conj(psi_s) i_s) on its shaft.

    The winding voltage's space phasor is the supply's: sqrt(2) V e^(j (theta - pi/2)) in delta (phase 1's
    voltage a sine of the angle theta, theta' = 2 pi f), sqrt(2/3) V e^(j (theta - pi/2 - pi/6)) in star, V and f
    signals of time, zero until the supply is switched on (a step of a table: a segment boundary), star until
    a star-delta starter switches (another).  The electrical energy it takes in, 3/2 Re(v conj(i_s)), and its
    copper losses, 3/2 (R_s |i_s|^2 + R_r |i_r|^2), are states (the ledger's work and loss); the magnetic energy
    3/4 Re(psi_s conj(i_s) + psi_r conj(i_r)) is stored.  Each peak of the stator current's magnitude and each
    turn of the torque is a row (an observation), so the summary's ``<name>_peak_current``, ``_max_torque`` and
    ``_min_torque`` are exact.
    """

    stator_resistance: object  # R_s, ohm
    rotor_resistance: object  # R_r, ohm
    stator_inductance: object  # L_ss + L_m, H
    rotor_inductance: object  # L_rs + L_m, H
    main_inductance: object  # L_m, H
    rotor_inertia: object  # kg*m^2
    phase: object  # rad, phase 1's at t = 0
    on_times: object  # s: the supply's switch, a table of time (0 off, 1 on)
    on_values: object
    delta_times: object  # s: the windings' connection, a table of time (0 star, 1 delta)
    delta_values: object
    voltage_times: object
    voltage_values: object  # V, line-to-line RMS
    voltage_amplitudes: object
    voltage_frequencies: object
    voltage_phases: object
    frequency_times: object
    frequency_values: object  # Hz
    frequency_amplitudes: object
    frequency_frequencies: object
    frequency_phases: object
    voltage_envelope_times: object = None
    voltage_envelope_values: object = None
    frequency_envelope_times: object = None
    frequency_envelope_values: object = None
    pole_pairs: int = static(2)
    shaft: str = static("")
    section: str = static("")  # its key in drivetrain.induction_machines

    @classmethod
    def from_spec(cls, spec) -> "InductionMachine":
        supply = spec.supply
        on = (0.0, supply.on_at, supply.on_at), (0.0, 0.0, 1.0)
        if supply.on_at == 0.0:
            on = (0.0, 0.0, 0.0), (1.0, 1.0, 1.0)  # on from the start (three rows: the same structure)
        if supply.connection == "star_delta":
            delta = (0.0, supply.delta_at, supply.delta_at), (0.0, 0.0, 1.0)
        else:
            connected = 1.0 if supply.connection == "delta" else 0.0
            delta = (0.0, 0.0, 0.0), (connected, connected, connected)
        return cls(stator_resistance=spec.stator_resistance, rotor_resistance=spec.rotor_resistance,
                   stator_inductance=spec.stator_leakage + spec.main_inductance,
                   rotor_inductance=spec.rotor_leakage + spec.main_inductance, main_inductance=spec.main_inductance,
                   rotor_inertia=spec.rotor_inertia, phase=supply.phase, on_times=np.asarray(on[0]),
                   on_values=np.asarray(on[1]), delta_times=np.asarray(delta[0]), delta_values=np.asarray(delta[1]),
                   **signal_fields(supply.voltage, "voltage"), **signal_fields(supply.frequency, "frequency"),
                   pole_pairs=spec.pole_pairs, shaft=spec.shaft, section=spec.name)

    # ------------------------------------------------------------------------------------------------ its states
    @property
    def flux_states(self) -> tuple:
        name = self.section
        return (f"{name}_stator_flux_a", f"{name}_stator_flux_b", f"{name}_rotor_flux_a", f"{name}_rotor_flux_b")

    @property
    def angle_state(self) -> str:
        return f"{self.section}_supply_angle"

    @property
    def observation_kinds(self) -> tuple:
        return (f"{self.section}_current_peak", f"{self.section}_torque_turn")

    @property
    def crossings(self) -> tuple:  # the torque's turns either way: its peaks and its troughs are rows
        return (f"{self.section}_torque_turn",)

    @property
    def summaries(self) -> dict:
        name = self.section
        return {f"{name}_peak_current": "A", f"{name}_max_torque": "N*m", f"{name}_min_torque": "N*m"}

    @property
    def columns(self) -> dict:
        name = self.section
        return {f"{name}_current": ("A", f"stator current of induction machine {name}: its space phasor's "
                                         "magnitude, a phase current's amplitude"),
                f"{name}_torque": ("N*m", f"air-gap torque of induction machine {name} on shaft {self.shaft}, "
                                          "positive in the shaft's positive sense"),
                f"{name}_voltage": ("V", f"winding voltage of induction machine {name}: its space phasor's "
                                         "magnitude, a winding's amplitude"),
                f"{name}_power": ("W", f"electrical power induction machine {name} takes in")}

    def tables(self) -> dict:
        return {**signal_tables(self, "voltage"), **signal_tables(self, "frequency"),
                f"{self.section}.on": ("on_times", "on_values"), f"{self.section}.delta": ("delta_times",
                                                                                       "delta_values")}

    def states(self) -> dict:
        return {**{state: 0.0 for state in self.flux_states}, self.angle_state: self.phase, self.input_state: 0.0,
                self.copper_state: 0.0}

    # ------------------------------------------------------------------------------------------- its quantities
    def fluxes(self, x):
        """(psi_s, psi_r), complex, V*s: the stator's and the rotor's flux linkages in the stator's frame."""
        sa, sb, ra, rb = (x.state(state) for state in self.flux_states)
        return sa + 1j * sb, ra + 1j * rb

    def currents(self, x):
        """(i_s, i_r), complex, A: from the fluxes through the inverse of the inductance matrix."""
        psi_s, psi_r = self.fluxes(x)
        det = self.stator_inductance * self.rotor_inductance - self.main_inductance ** 2
        return ((self.rotor_inductance * psi_s - self.main_inductance * psi_r) / det,
                (self.stator_inductance * psi_r - self.main_inductance * psi_s) / det)

    def winding_voltage(self, x):
        """v_s, complex, V: the supply's space phasor as the windings are connected, 0 until switched on."""
        rms = signal_at(self, x, "voltage") * x.table(f"{self.section}.on")
        delta = x.table(f"{self.section}.delta")
        amplitude = math.sqrt(2.0) * rms * (delta + (1.0 - delta) / math.sqrt(3.0))
        angle = x.state(self.angle_state) + SINE + DELTA_LEAD * (delta - 1.0)
        return amplitude * jnp.exp(1j * angle)

    def air_gap_torque(self, x):
        psi_s, _ = self.fluxes(x)
        i_s, _ = self.currents(x)
        return HALF_PHASES * self.pole_pairs * jnp.imag(jnp.conj(psi_s) * i_s)

    def inertias(self) -> tuple:
        return ((self.shaft, self.rotor_inertia),)

    def torques(self, x) -> tuple:
        return ((self.shaft, self.air_gap_torque(x)),)

    def rates(self, x) -> dict:
        psi_s, psi_r = self.fluxes(x)
        i_s, i_r = self.currents(x)
        voltage = self.winding_voltage(x)
        stator = voltage - self.stator_resistance * i_s
        rotor = -self.rotor_resistance * i_r + 1j * self.pole_pairs * x.speed(self.shaft) * psi_r
        sa, sb, ra, rb = self.flux_states
        return {sa: jnp.real(stator), sb: jnp.imag(stator), ra: jnp.real(rotor), rb: jnp.imag(rotor),
                self.angle_state: 2.0 * math.pi * signal_at(self, x, "frequency"),
                self.input_state: HALF_PHASES * jnp.real(voltage * jnp.conj(i_s)),
                self.copper_state: HALF_PHASES * (self.stator_resistance * jnp.abs(i_s) ** 2
                                                  + self.rotor_resistance * jnp.abs(i_r) ** 2)}

    def _changes(self, x):
        """(di_s/dt, dtau/dt): the stator current's and the air-gap torque's rates."""
        rates = self.rates(x)
        sa, sb, ra, rb = self.flux_states
        d_psi_s, d_psi_r = rates[sa] + 1j * rates[sb], rates[ra] + 1j * rates[rb]
        det = self.stator_inductance * self.rotor_inductance - self.main_inductance ** 2
        d_i_s = (self.rotor_inductance * d_psi_s - self.main_inductance * d_psi_r) / det
        psi_s, _ = self.fluxes(x)
        i_s, _ = self.currents(x)
        d_torque = HALF_PHASES * self.pole_pairs * jnp.imag(jnp.conj(d_psi_s) * i_s + jnp.conj(psi_s) * d_i_s)
        return d_i_s, d_torque

    def observations(self, x) -> dict:
        # the current's magnitude peaks where Re(conj(i_s) di_s/dt) falls through zero, the torque turns where its
        # rate changes sign: rows, so the summary's peaks are exact
        d_i_s, d_torque = self._changes(x)
        i_s, _ = self.currents(x)
        return {f"{self.section}_current_peak": jnp.real(jnp.conj(i_s) * d_i_s),
                f"{self.section}_torque_turn": d_torque}

    def extremes(self, x) -> dict:
        name, torque = self.section, self.air_gap_torque(x)
        return {f"{name}_peak_current": ("max", jnp.abs(self.currents(x)[0])), f"{name}_max_torque": ("max", torque),
                f"{name}_min_torque": ("min", torque)}

    def ledger(self, x) -> dict:
        psi_s, psi_r = self.fluxes(x)
        i_s, i_r = self.currents(x)
        return self.electrical_ledger(x, 0.5 * HALF_PHASES * jnp.real(psi_s * jnp.conj(i_s) + psi_r * jnp.conj(i_r)))

    def outputs(self, x) -> dict:
        name = self.section
        i_s, _ = self.currents(x)
        voltage = self.winding_voltage(x)
        return {f"{name}_current": jnp.abs(i_s), f"{name}_torque": self.air_gap_torque(x),
                f"{name}_voltage": jnp.abs(voltage), f"{name}_power": HALF_PHASES * jnp.real(voltage * jnp.conj(i_s))}

"""A friction clutch: between two shafts, or a shaft and the ground (a brake); the hoist's cone clutch is one."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp
import numpy as np

from ..._pytree import static
from ..core.element import SLIP_BACKWARD, SLIP_FORWARD, STUCK
from ._signal import harmonics_step, signal_at, signal_fields, signal_tables
from ._names import NamedOutputs, called
from ._knots import interpolate, knots_passed
from ._slip_heat import AbstractSlipHeat
from ._slip_table import along_slip, slip_columns, slip_knots

# what each of its outputs is, by its role (named <name>_<role>)
_COLUMNS = {
    "torque": ("N*m", "torque {clutch} passes from the {a} shaft to {b}, positive when the {a} shaft drives"),
    "slip": ("rad/s", "speed of the {a} shaft less that of {b}"),
    "locked": ("1", "1 while {clutch} sticks, 0 while it slips or is open"),
    "force": ("N", "force pressing {clutch} (at or below zero it is open)"),
    "energy": ("J", "energy dissipated in {clutch} so far"),
    "capacity": ("N*m", "static torque capacity of {clutch} at the force pressing it"),
    "mode": ("1", "0 locked, 1 slipping forwards, 2 slipping backwards, 3 open"),
}
_SUMMARIES = {"lockup_time": "s", "slip_duration": "s", "peak_torque": "N*m", "peak_slip_speed": "rad/s",
              "slip_energy": "J"}
# between masses (a brake on a line): a friction force where a shaft's clutch passes a torque, N and m/s
LINE_ROLES = {"torque": "friction", "peak_torque": "peak_friction"}
LINE_UNITS = {"N*m": "N", "rad/s": "m/s"}
_LINE_TEXT = {"torque": "friction force {clutch} passes from mass {a} to {b}, positive when mass {a} drives",
              "slip": "velocity of mass {a} less that of {b}",
              "capacity": "static friction force of {clutch} at the force pressing it"}


class FrictionClutch(NamedOutputs, AbstractSlipHeat):
    """Faces pressed by a force F(t), a time signal: static capacity mu_s c F and sliding torque mu_k c F,
    c = effective radius times surfaces (Modelica's ``cgeo``; a cone's n r_m / sin(beta)), nothing where
    F <= 0.  Its halves' inertias sit on the shafts it joins; its friction coefficients may depend on its
    faces' temperature (the state ``<name>_temperature``, a clutch heating's), as tables.

    A force given as a table is open over any segment where it stays at or below zero (where it
    crosses zero between two rows is a segment boundary, like the rows); a force in
    harmonics may cross zero anywhere, so its sign is watched: the crossing is found like a switch
    (events ``disengage`` falling, ``engage`` rising) and no step straddles the kink of max(F, 0).  Its
    heat of slip is a state and a loss of the ledger; its events carry its name.  Its kinetic friction may be a
    table of the slip speed's size instead (Modelica's mu_pos; knots that no step straddles either).
    """

    static_friction: object
    kinetic_friction: object
    torque_per_newton: object  # m: effective radius times surfaces
    force_times: object  # s
    force_values: object  # N
    force_amplitudes: object  # N
    force_frequencies: object  # Hz
    force_phases: object  # rad
    force_envelope_times: object = None  # s, the harmonics' envelope (None: none)
    force_envelope_values: object = None
    driving_inertia: object = 0.0  # kg*m^2, its half on shaft a
    driven_inertia: object = 0.0  # kg*m^2, its half on shaft b
    # friction against the faces' temperature (both tables on the knots of either), in place of the constants
    # where ``fades``
    friction_temperatures: object = None  # K
    static_frictions: object = None
    kinetic_frictions: object = None
    # the kinetic friction against the slip speed's size (a table), in place of the constant where ``slip_varies``
    slip_speeds: object = None  # rad/s
    slip_frictions: object = None
    on_line: bool = static(False)  # between masses: a friction force (N), a slip in m/s
    driving: str = static("")  # shaft a
    driven: str | None = static(None)  # shaft b, None for the ground
    section: str = static("")  # the clutch's name
    in_harmonics: bool = static(False)
    fades: bool = static(False)
    slip_varies: bool = static(False)

    observation_kinds: ClassVar[tuple] = ("clutch_force",)
    crossings: ClassVar[tuple] = ("clutch_force",)
    crossing_events: ClassVar[dict] = {"clutch_force": ("engage", "disengage")}

    @classmethod
    def from_spec(cls, spec) -> "FrictionClutch":
        a, b = spec.between
        driving_inertia, driven_inertia = spec.resolved("halves")
        fade = spec.fade()  # friction against the faces' temperature, or (never both) against the slip speed
        law = {} if fade is None else {"friction_temperatures": fade["temperatures"], "fades": True,
                                       "static_frictions": fade["static"], "kinetic_frictions": fade["kinetic"]}
        law.update(slip_columns(spec.slip_table, "slip_frictions"))
        return cls(static_friction=spec.static_friction, kinetic_friction=spec.kinetic_at_rest,
                   torque_per_newton=spec.torque_per_newton, **signal_fields(spec.force, "force"),
                   driving_inertia=driving_inertia, driven_inertia=driven_inertia, on_line=spec.resolved("on_line"),
                   driving=a,
                   driven=None if b == "ground" else b, section=spec.name, in_harmonics=spec.force.has_harmonics,
                   **law)

    @property
    def heat_state(self) -> str:
        return f"{self.section}_energy"

    def role_name(self, role: str) -> str:
        """An output's name by its role: ``<name>_<role>``, on a line a friction where a shaft's has a torque."""
        return self.named(f"{{name}}_{LINE_ROLES.get(role, role) if self.on_line else role}")

    def _units(self, units: str) -> str:
        return LINE_UNITS.get(units, units) if self.on_line else units

    @property
    def summaries(self) -> dict:
        return {self.role_name(role): self._units(units) for role, units in _SUMMARIES.items()}

    @property
    def columns(self) -> dict:
        if self.on_line:
            b = f"mass {self.driven}" if self.driven else "the ground"
            texts = {role: _LINE_TEXT.get(role, text) for role, (_, text) in _COLUMNS.items()}
        else:
            b = f"the {self.driven} shaft" if self.driven else "the ground"
            texts = {role: text for role, (_, text) in _COLUMNS.items()}
        return {self.role_name(role): (self._units(units), texts[role].format(clutch=called("clutch", self.section),
                                                                     a=self.driving, b=b))
                for role, (units, _) in _COLUMNS.items()}

    def joins(self) -> tuple:
        return (self.driving, self.driven)

    def inertias(self) -> tuple:
        halves = ((self.driving, self.driving_inertia),)
        return halves + ((self.driven, self.driven_inertia),) if self.driven else halves

    def tables(self) -> dict:
        return signal_tables(self, "force")

    def force(self, x):
        return signal_at(self, x, "force")

    def longest_step(self):
        return harmonics_step(self, "force")

    def pressing(self, x):
        """The force that presses the faces: F, or 0 where F <= 0 (the clutch is open)."""
        return jnp.maximum(self.force(x), 0.0)

    def friction(self, x):
        """(static, kinetic) friction coefficients now: the constants, or the tables at the faces' temperature,
        or the kinetic one at the slip speed's size."""
        if self.slip_varies:
            return self.static_friction, along_slip(x, self.section, self.slip_speeds, self.slip_frictions)
        if not self.fades:
            return self.static_friction, self.kinetic_friction
        temperature = x.state(f"{self.section}_temperature")
        return (interpolate(temperature, self.friction_temperatures, self.static_frictions),
                interpolate(temperature, self.friction_temperatures, self.kinetic_frictions))

    def capacity(self, x):
        return self.friction(x)[0] * self.torque_per_newton * self.pressing(x)

    def sliding_torque(self, x):
        return self.friction(x)[1] * self.torque_per_newton * self.pressing(x)

    def kink_names(self) -> tuple:
        return ("friction_knots",) if self.fades or self.slip_varies else ()

    def kinks(self, x) -> dict:
        # the friction's slope changes at each knot of its tables: no step straddles one
        if self.slip_varies:
            return {"friction_knots": slip_knots(x, self.section, self.slip_speeds)}
        if not self.fades:
            return {}
        return {"friction_knots": knots_passed(x.state(f"{self.section}_temperature"), self.friction_temperatures)}

    def boundaries(self) -> tuple:
        """Where the force table crosses zero between two knots: a segment boundary, like the knots, so
        that the kink of max(F, 0) is never inside a segment (one per interval, at its start where the
        force does not cross: the count is the table's structure, the times its numbers)."""
        t, v = np.asarray(self.force_times, float), np.asarray(self.force_values, float)  # on the host, as knots
        if t.shape[-1] < 2:
            return ()
        t0, t1, v0, v1 = t[..., :-1], t[..., 1:], v[..., :-1], v[..., 1:]
        crosses = (v0 * v1 < 0.0) & (t1 > t0)
        at = np.where(crosses, t0 + v0 / np.where(crosses, v0 - v1, 1.0) * (t1 - t0), t0)
        return tuple(at[..., i] for i in range(at.shape[-1]))

    def is_open(self, segment):
        if self.in_harmonics:
            return False
        # the force's sign holds over a segment (its zeros are boundaries): the middle's decides
        value, slope = segment.lines[f"{self.section}.force"]
        return value + slope * 0.5 * (segment.end - segment.start) <= 0.0

    def observes(self, kind: str) -> bool:
        return self.in_harmonics

    def observations(self, x) -> dict:
        if not self.in_harmonics:
            return {}
        return {"clutch_force": self.force(x)}

    def extremes(self, x) -> dict:
        mode = x.mode(self.section)
        return {
            self.named("{name}_lockup_time"): ("first", mode == STUCK),
            self.named("{name}_slip_duration"): ("duration", (mode == SLIP_FORWARD) | (mode == SLIP_BACKWARD)),
            self.role_name("peak_torque"): ("max", jnp.abs(x.coupling_torque(self.section))),
            self.named("{name}_peak_slip_speed"): ("max", jnp.abs(x.relative_speed(self.section))),
        }

    def summary(self, x) -> dict:
        return {self.named("{name}_slip_energy"): x.state(self.heat_state)}

    def outputs(self, x) -> dict:
        name, mode = self.section, x.mode(self.section)
        return {self.role_name("torque"): x.coupling_torque(name),
                self.named("{name}_slip"): x.relative_speed(name),
                self.named("{name}_locked"): (mode == STUCK).astype(jnp.int8),
                self.named("{name}_force"): self.force(x),
                self.named("{name}_energy"): x.state(self.heat_state),
                self.named("{name}_capacity"): self.capacity(x),
                self.named("{name}_mode"): mode.astype(jnp.int8)}

"""Bearing friction: a shaft's friction against the ground, or between two shafts, that depends on the slip speed."""

from __future__ import annotations

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import STUCK
from ._slip_heat import AbstractSlipHeat
from ._slip_table import along_slip, slip_columns, slip_knots


class BearingFriction(AbstractSlipHeat):
    """Modelica's BearingFriction: stuck while the torque across it stays within its static torque (``peak``
    times its friction torque at rest), slipping either way at its friction torque, a constant or a table of
    the slip speed's size (whose knots no step straddles), or a Stribeck curve: a constant, an excess at rest
    decaying with the slip's size, and a viscous term.  Its heat of slip is a state and a loss of the
    ledger; its locks and unlocks are events named after it.  Outputs ``<name>_torque`` (what it passes from
    shaft a to b, or to the ground), ``<name>_slip``, ``<name>_locked``, ``<name>_energy`` (its heat so far);
    summaries ``<name>_slip_energy`` (that heat at the end) and ``<name>_slip_duration``: a clutch's names, each a
    series or a summary, never both (a results file holds them side by side).  On a line (Modelica's
    SupportFriction, a mass's friction) a friction force: ``<name>_friction`` in N, its slip in m/s.
    """

    static_torque: object  # N*m, the most it holds stuck
    kinetic_torque: object  # N*m, its friction torque (a constant; the Stribeck curve's Coulomb part)
    slip_speeds: object = None  # rad/s, the table's (in place of the constant where ``slip_varies``)
    slip_torques: object = None  # N*m
    # a constant friction's Stribeck curve, numbers of its program (0: none), so that a new value compiles nothing
    stribeck: object = 0.0  # N*m, the excess at rest
    decay: object = 0.0  # s/rad
    viscous: object = 0.0  # N*m*s/rad
    driving: str = static("")  # shaft a
    driven: str | None = static(None)  # shaft b, None for the ground
    section: str = static("")
    slip_varies: bool = static(False)
    on_line: bool = static(False)  # between masses: a friction force (N), a slip in m/s

    @classmethod
    def from_spec(cls, spec) -> "BearingFriction":
        a, b = spec.sides
        varying = slip_columns(spec.slip_table, "slip_torques")
        return cls(static_torque=spec.peak * spec.torque_at_rest,
                   kinetic_torque=spec.torque_at_rest - spec.stribeck, stribeck=spec.stribeck, decay=spec.decay,
                   viscous=spec.viscous, driving=a, driven=None if b == "ground" else b, section=spec.name, **varying,
                   on_line=spec.force is not None)

    @property
    def heat_state(self) -> str:
        return f"{self.section}_energy"

    @property
    def summaries(self) -> dict:
        return {f"{self.section}_slip_energy": "J", f"{self.section}_slip_duration": "s"}

    @property
    def passed(self) -> str:
        """The column of what it passes: ``<name>_torque``, on a line ``<name>_friction``."""
        return f"{self.section}_{'friction' if self.on_line else 'torque'}"

    @property
    def columns(self) -> dict:
        name, a = self.section, self.driving
        body, (what, units, speed) = ("mass", ("force", "N", "velocity")) if self.on_line else \
            ("shaft", ("torque", "N*m", "speed"))
        b = f"{body} {self.driven}" if self.driven else "the ground"
        return {self.passed: (units, f"friction {what} {name} passes from {body} {a} to {b}, positive when "
                                     f"{a} drives"),
                f"{name}_slip": ("m/s" if self.on_line else "rad/s", f"{speed} of {body} {a} less that of {b}"),
                f"{name}_locked": ("1", f"1 while {name} sticks, 0 while it slips"),
                f"{name}_energy": ("J", f"energy dissipated in {name} so far")}

    def joins(self) -> tuple:
        return (self.driving, self.driven)

    def capacity(self, x):
        return self.static_torque

    def sliding_torque(self, x):
        if self.slip_varies:
            return along_slip(x, self.section, self.slip_speeds, self.slip_torques)
        # its Stribeck curve (Modelica's MassWithStopAndFriction: F_Coulomb + F_Stribeck exp(-fexp |v|) + F_prop |v|)
        slip = jnp.abs(x.relative_speed(self.section))
        return self.kinetic_torque + self.stribeck * jnp.exp(-self.decay * slip) + self.viscous * slip

    def kink_names(self) -> tuple:
        return ("friction_knots",) if self.slip_varies else ()

    def kinks(self, x) -> dict:
        return {"friction_knots": slip_knots(x, self.section, self.slip_speeds)} if self.slip_varies else {}

    def extremes(self, x) -> dict:
        return {f"{self.section}_slip_duration": ("duration", x.mode(self.section) != STUCK)}

    def summary(self, x) -> dict:
        return {f"{self.section}_slip_energy": x.state(self.heat_state)}

    def outputs(self, x) -> dict:
        name = self.section
        return {self.passed: x.coupling_torque(name), f"{name}_slip": x.relative_speed(name),
                f"{name}_locked": (x.mode(name) == STUCK).astype(jnp.int8),
                f"{name}_energy": x.state(self.heat_state)}

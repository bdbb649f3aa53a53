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
    the slip speed's size (whose knots no step straddles).  Its heat of slip is a state and a loss of the
    ledger; its locks and unlocks are events named after it.  Outputs ``<name>_torque`` (what it passes from
    shaft a to b, or to the ground), ``<name>_slip``, ``<name>_locked``, ``<name>_energy`` (its heat so far);
    summaries ``<name>_slip_energy`` (that heat at the end) and ``<name>_slip_duration``: a clutch's names, each a
    series or a summary, never both (a results file holds them side by side).
    """

    static_torque: object  # N*m, the most it holds stuck
    kinetic_torque: object  # N*m, its friction torque (a constant)
    slip_speeds: object = None  # rad/s, the table's (in place of the constant where ``slip_varies``)
    slip_torques: object = None  # N*m
    driving: str = static("")  # shaft a
    driven: str | None = static(None)  # shaft b, None for the ground
    section: str = static("")
    slip_varies: bool = static(False)

    @classmethod
    def from_spec(cls, spec) -> "BearingFriction":
        a, b = spec.sides
        varying = slip_columns(spec.slip_table, "slip_torques")
        return cls(static_torque=spec.peak * spec.torque_at_rest, kinetic_torque=spec.torque_at_rest, driving=a,
                   driven=None if b == "ground" else b, section=spec.name, **varying)

    @property
    def heat_state(self) -> str:
        return f"{self.section}_energy"

    @property
    def summaries(self) -> dict:
        return {f"{self.section}_slip_energy": "J", f"{self.section}_slip_duration": "s"}

    @property
    def columns(self) -> dict:
        name, a = self.section, self.driving
        b = f"shaft {self.driven}" if self.driven else "the ground"
        return {f"{name}_torque": ("N*m", f"friction torque {name} passes from shaft {a} to {b}, positive when "
                                          f"{a} drives"),
                f"{name}_slip": ("rad/s", f"speed of shaft {a} less that of {b}"),
                f"{name}_locked": ("1", f"1 while {name} sticks, 0 while it slips"),
                f"{name}_energy": ("J", f"energy dissipated in {name} so far")}

    def joins(self) -> tuple:
        return (self.driving, self.driven)

    def capacity(self, x):
        return self.static_torque

    def sliding_torque(self, x):
        return along_slip(x, self.section, self.slip_speeds, self.slip_torques) if self.slip_varies \
            else self.kinetic_torque

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
        return {f"{name}_torque": x.coupling_torque(name), f"{name}_slip": x.relative_speed(name),
                f"{name}_locked": (x.mode(name) == STUCK).astype(jnp.int8),
                f"{name}_energy": x.state(self.heat_state)}

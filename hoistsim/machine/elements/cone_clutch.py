"""The cone clutch between the motor shaft and the pinion shaft."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp
import numpy as np

from ... import components
from ..._pytree import static
from ..core.element import SLIP_BACKWARD, SLIP_FORWARD, STUCK
from ._slip_heat import AbstractSlipHeat


class ConeClutch(AbstractSlipHeat):
    """A friction coupling pressed by an engagement force F(t), a table of time.

    Static capacity f_a c F and sliding torque f c F, with the geometry constant
    c = n r_m / sin(beta) (:class:`hoistsim.components.ConeClutch`); open while
    the force is zero.  Its halves' inertias sit on the two shafts it joins.
    The heat of slip (torque times slip speed) is a state and a loss of the ledger.
    """

    clutch_constant: object  # c = n r_m / sin(beta), m
    static_friction: object  # f_a
    kinetic_friction: object  # f
    force_times: object  # s, the engagement force table (a repeated time is a step)
    force_values: object  # N
    driving_inertia: object  # kg*m^2, the half on the motor shaft
    driven_inertia: object  # kg*m^2, the half on the pinion shaft
    # friction against the surfaces' temperature (clutch_heating's tables, both on the knots of either),
    # in place of the constants where ``fades``; the temperature is clutch_heating's state
    friction_temperatures: object = None  # K
    static_frictions: object = None
    kinetic_frictions: object = None
    fades: bool = static(False)

    section: ClassVar[str] = "clutch"
    heat_state: ClassVar[str] = "clutch_energy"
    summaries: ClassVar[dict] = {"lockup_time": "s", "slip_duration": "s", "peak_clutch_torque": "N*m",
                                 "peak_slip_speed": "rad/s", "slip_energy": "J"}
    columns: ClassVar[dict] = {
        "slip_speed": ("rad/s", "motor speed minus clutch-output (pinion) speed"),
        "clutch_torque": ("N*m", "torque through the clutch, positive when the motor drives the load"),
        "clutch_locked": ("1", "1 while the clutch sticks, 0 while it slips or is open"),
        "engagement_force": ("N", "axial force pressing the cone clutch"),
        "clutch_energy": ("J", "energy dissipated in the clutch so far"),
        "clutch_capacity": ("N*m", "static torque capacity at the current engagement force"),
        "clutch_mode": ("1", "0 locked, 1 slipping forwards, 2 slipping backwards, 3 open"),
    }

    @classmethod
    def from_spec(cls, spec, scenario) -> "ConeClutch":
        geometry = components.ConeClutch(spec.inner_radius, spec.outer_radius, spec.half_angle,
                                         spec.static_friction, spec.kinetic_friction, spec.surfaces,
                                         spec.mean_radius)
        table = spec.engagement_force
        heating = scenario.clutch_heating
        fading = fade_tables(heating, spec) if heating is not None and heating.fades else {}
        return cls(clutch_constant=geometry.torque_per_newton, static_friction=spec.static_friction,
                   kinetic_friction=spec.kinetic_friction, force_times=np.asarray(table.times, float),
                   force_values=np.asarray(table.forces, float), driving_inertia=spec.driving_inertia,
                   driven_inertia=spec.driven_inertia, **fading)

    def joins(self) -> tuple:
        return ("motor", "pinion")

    def tables(self) -> dict:
        return {"engagement_force": ("force_times", "force_values")}

    def friction(self, x):
        """(static, kinetic) friction coefficients now: the constants, or the tables at the temperature."""
        if not self.fades:
            return self.static_friction, self.kinetic_friction
        temperature = x.state("clutch_temperature")
        return (jnp.interp(temperature, self.friction_temperatures, self.static_frictions),
                jnp.interp(temperature, self.friction_temperatures, self.kinetic_frictions))

    def capacity(self, x):
        return self.friction(x)[0] * self.clutch_constant * x.table("engagement_force")

    def sliding_torque(self, x):
        return self.friction(x)[1] * self.clutch_constant * x.table("engagement_force")

    def kink_names(self) -> tuple:
        return ("friction_knots",) if self.fades else ()

    def kinks(self, x) -> dict:
        # the friction's slope changes at each knot of its tables: no step straddles one
        if not self.fades:
            return {}
        return {"friction_knots": knots_passed(x.state("clutch_temperature"), self.friction_temperatures)}

    def is_open(self, segment):
        return segment.zero_throughout("engagement_force")

    def inertias(self) -> tuple:
        return (("motor", self.driving_inertia), ("pinion", self.driven_inertia))

    def extremes(self, x) -> dict:
        mode = x.mode("clutch")
        return {
            "lockup_time": ("first", mode == STUCK),
            "slip_duration": ("duration", (mode == SLIP_FORWARD) | (mode == SLIP_BACKWARD)),
            "peak_clutch_torque": ("max", jnp.abs(x.coupling_torque("clutch"))),
            "peak_slip_speed": ("max", jnp.abs(x.relative_speed("clutch"))),
        }

    def outputs(self, x) -> dict:
        mode = x.mode("clutch")
        return {
            "slip_speed": x.relative_speed("clutch"),
            "clutch_torque": x.coupling_torque("clutch"),
            "clutch_locked": (mode == STUCK).astype(jnp.int8),
            "engagement_force": x.table("engagement_force"),
            "clutch_energy": x.state("clutch_energy"),
            "clutch_capacity": self.capacity(x),
            "clutch_mode": mode.astype(jnp.int8),
        }

    def summary(self, x) -> dict:
        return {"slip_energy": x.state("clutch_energy")}


# Beyond the tables' last knot the knot coordinate grows by one every this many kelvin: steadily, so that no
# crossing is missed, and slowly, so that the whole numbers it passes there (no knots) are 1e6 K apart.
BEYOND_THE_TABLE = 1e6  # K


def knots_passed(temperature, knots):
    """The tables' knots counted along the temperature: a whole number exactly at each knot, rising
    steadily with the temperature everywhere (below the first knot, -1 at absolute zero)."""
    inside = jnp.interp(temperature, knots, jnp.arange(knots.shape[0], dtype=knots.dtype))
    below = (temperature - knots[0]) / knots[0]
    above = knots.shape[0] - 1 + (temperature - knots[-1]) / BEYOND_THE_TABLE
    return jnp.where(temperature < knots[0], below, jnp.where(temperature > knots[-1], above, inside))


def fade_tables(heating, spec) -> dict:
    """The clutch's fields for friction against temperature: clutch_heating's tables (a table not given is
    the clutch's constant), both on the knots of either, which leaves each unchanged (linear between)."""
    given = [table for table in (heating.static_friction, heating.kinetic_friction) if table is not None]
    knots = np.asarray(sorted({row[0] for table in given for row in table}), float)

    def on_knots(table, constant):
        if table is None:
            return np.full(knots.shape, float(constant))
        temperatures, values = (np.asarray(column, float) for column in zip(*table))
        return np.interp(knots, temperatures, values)

    return {"friction_temperatures": knots, "static_frictions": on_knots(heating.static_friction, spec.static_friction),
            "kinetic_frictions": on_knots(heating.kinetic_friction, spec.kinetic_friction), "fades": True}

"""The periodic regime of the motor shaft: each period marked, the extremes of speed and energy found."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import STUCK, AbstractElement


class PeriodicRegime(AbstractElement):
    """periodic: what the analysis of the periodic regime reads from a run's rows.

    - every period of the machine (motor angle a whole multiple of it) is a
      row of kind ``period``, and ends a cycle (a clutch that slips and relocks
      every period is judged per period, not over the run);
    - the motor shaft's speed maxima and minima are rows (``speed_max``,
      ``speed_min``: its acceleration through zero), found by root-finding,
      never sampled;
    - so are the kinetic energy's extremes (``energy_max``, ``energy_min``),
      where they differ from the speed's: while a coupling slips, or where an
      inertia varies with angle;
    - the integral of the speed over the angle turned, a state, gives the
      seed's mean speed over a period, (1/Theta) integral of w dtheta.
    Built for every machine with a ripple or a slider-crank, and with ``periodic:``.
    """

    period: object  # rad of motor angle: the machine's period (scenario.period)
    inertia_varies_with_angle: bool = static(False)  # the energy guards stay on even while all is stuck

    section: ClassVar[str] = "periodic"
    cycles: ClassVar[dict] = {"periods": "period"}
    observation_kinds: ClassVar[tuple] = ("speed_max", "speed_min", "energy_max", "energy_min")
    columns: ClassVar[dict] = {"kinetic_energy": ("J", "kinetic energy of the whole machine")}

    @classmethod
    def from_spec(cls, spec) -> "PeriodicRegime":
        return cls(period=spec.resolved("period"),
                   inertia_varies_with_angle=spec.resolved("inertia_varies_with_angle"))

    def angles(self) -> tuple:
        return ("motor",)

    def kink_names(self) -> tuple:
        return ("periods",)

    def cycle_angle(self):
        return self.period

    def kinks(self, x) -> dict:
        return {"periods": x.angle("motor") / self.period}

    def states(self) -> dict:
        return {"speed_angle_integral": 0.0}

    def rates(self, x) -> dict:
        # d/dt of the integral of w dtheta: w * dtheta/dt = w^2
        return {"speed_angle_integral": x.speed("motor") ** 2}

    def observations(self, x) -> dict:
        acceleration = x.acceleration("motor")
        # With the machine rigid and its inertia constant, energy and speed peak together: one row will do.
        apart = jnp.any(x.modes != STUCK) if x.modes.shape[0] else jnp.zeros((), bool)
        if self.inertia_varies_with_angle:
            apart = jnp.ones((), bool)
        power = jnp.where(apart, x.kinetic_power(), 1.0)
        return {"speed_max": acceleration, "speed_min": -acceleration,
                "energy_max": power, "energy_min": jnp.where(apart, -power, 1.0)}

    def outputs(self, x) -> dict:
        return {"kinetic_energy": x.kinetic_energy()}

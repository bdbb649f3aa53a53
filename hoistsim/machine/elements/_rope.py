"""What both ropes share: an elastic rope from the drum's rope point to the load, taut or slack."""

from __future__ import annotations

import abc
from typing import ClassVar

import jax.numpy as jnp

from ..core.element import AbstractElement


class AbstractRope(AbstractElement):
    """A rope of stiffness k and viscous damping c between the drum's rope point and the load: a load's
    ``rope``, built from the load that hangs on it.

    Its stretch s = x_d - x + s_0 (x_d the rope the drum has wound on since
    the start, x the load's height, s_0 the stretch at the start: M g / k for a
    load hanging on it, minus the initial slack) is a state, integrated from
    its own rate (rope speed at the drum less the load's speed): a few
    millimetres are not left to the difference of two heights of metres.
    Taut (s >= 0 and k s + c s' > 0) it pulls the load up and the drum down
    with F = k s + c s'; slack, exactly 0: a rope cannot push.  Where
    min(k s, k s + c s') changes sign the law changes: the integration stops
    exactly there and records ``rope_taut`` or ``rope_slack`` (a rope taut but
    unloaded, s = 0 with nothing pulling, crosses nothing).
    Ledger: the strain energy 1/2 k s^2 while stretched, and what the damper
    and a stretched rope's slackening shed, (F - k max(s, 0)) s' >= 0.
    The peak force is a row of its own (``rope_force_peak``), so the summary's
    peak and the dynamic factor (peak over the weight M g) are exact.
    """

    damping: object  # c, N*s/m
    initial_stretch: object  # s_0, m
    weight: object  # M g, N: the dynamic factor's reference

    section: ClassVar[str] = "rope"
    observation_kinds: ClassVar[tuple] = ("rope_state", "rope_force_peak")
    crossings: ClassVar[tuple] = ("rope_state",)
    crossing_events: ClassVar[dict] = {"rope_state": ("rope_taut", "rope_slack")}
    summaries: ClassVar[dict] = {"peak_rope_force": "N", "dynamic_factor": "1"}
    ledger_kinds: ClassVar[dict] = {"rope_strain_energy": "potential", "rope_damping_loss": "loss"}
    columns: ClassVar[dict] = {
        "rope_force": ("N", "rope tension, k s + c s' while taut, 0 while slack"),
        "rope_stretch": ("m", "rope stretch s (negative: the slack the rope hangs with)"),
        "rope_taut": ("1", "1 while the rope pulls, 0 while it is slack"),
    }

    @abc.abstractmethod
    def stiffness(self, x):
        """k (N/m) at this instant."""

    def stiffness_rate(self, x):
        """dk/dt (N/m/s): zero for a constant stiffness."""
        return 0.0

    def wound(self, x):
        """Rope the drum has wound on since the start (m; negative: paid out)."""
        return x.state("rope_stretch") - self.initial_stretch + x.angle("load")

    def stretch_rate(self, x):
        return x.speed("rope_point") - x.speed("load")

    def pull(self, x):
        """k s + c s': what the rope would pull with, were it taut (N)."""
        return self.stiffness(x) * x.state("rope_stretch") + self.damping * self.stretch_rate(x)

    def taut(self, x):
        return (x.state("rope_stretch") >= 0.0) & (self.pull(x) > 0.0)

    def force(self, x):
        """The rope's tension (N): its pull while taut, exactly 0 while slack."""
        return jnp.where(self.taut(x), self.pull(x), 0.0)

    def strain(self, x):
        """The stretch that stores energy: s where the rope is stretched, 0 where it hangs slack."""
        return jnp.maximum(x.state("rope_stretch"), 0.0)

    def torques(self, x) -> tuple:
        force = self.force(x)
        return (("rope_point", -force), ("load", force))

    def angles(self) -> tuple:
        return ("load",)  # the load's height (the mass load's position)

    def states(self) -> dict:
        return {"rope_stretch": self.initial_stretch, "rope_damping_loss": 0.0}

    def rates(self, x) -> dict:
        rate = self.stretch_rate(x)
        return {"rope_stretch": rate,
                "rope_damping_loss": (self.force(x) - self.stiffness(x) * self.strain(x)) * rate}

    def ledger(self, x) -> dict:
        return {"rope_strain_energy": 0.5 * self.stiffness(x) * self.strain(x) ** 2,
                "rope_damping_loss": x.state("rope_damping_loss")}

    def observations(self, x) -> dict:
        stretch = x.state("rope_stretch")
        # dF/dt while taut: k s' + c s'' + k' s (the accelerations from the bodies' solve)
        rate = (self.stiffness(x) * self.stretch_rate(x) + self.stiffness_rate(x) * stretch
                + self.damping * (x.acceleration("rope_point") - x.acceleration("load")))
        return {"rope_state": jnp.minimum(self.stiffness(x) * stretch, self.pull(x)),
                "rope_force_peak": jnp.where(self.taut(x), rate, 1.0)}

    def extremes(self, x) -> dict:
        force = self.force(x)
        return {"peak_rope_force": ("max", force), "dynamic_factor": ("max", force / self.weight)}

    def outputs(self, x) -> dict:
        return {"rope_force": self.force(x), "rope_stretch": x.state("rope_stretch"),
                "rope_taut": self.taut(x).astype(jnp.int8)}


def initial_stretch(load, gravity: float, stiffness: float) -> float:
    """The stretch at t = 0 (m): a load hanging on a taut rope carries its weight, M g / k; one resting
    on the ground or hanging with slack (which then falls) starts at minus the slack."""
    if load.ground is None and load.rope.initial_slack == 0.0:
        return load.mass * gravity / stiffness
    return -load.rope.initial_slack


def damping(load, stiffness: float) -> float:
    """c = 2 zeta sqrt(k M), k at t = 0 (N*s/m)."""
    return 2.0 * load.rope.damping_ratio * (stiffness * load.mass) ** 0.5

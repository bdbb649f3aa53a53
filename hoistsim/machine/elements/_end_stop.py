"""What a mass's two hard stops share: a contact with the ground at one end of its travel, met in an impact."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import STUCK, AbstractCoupling
from ._one_way import OneWayHold


class AbstractEndStop(OneWayHold, AbstractCoupling):
    """A hard stop at one end of a mass's travel (a drawn drivetrain's ``stops.<name>.lower`` or ``.upper``): a
    contact of the mass with the ground, its gap the distance the mass's centre has left before it stops.

    The mass meets it where the gap closes, in an impact: a rebound at ``restitution`` times the speed it met it
    at, or, where that rebound would be slower than ``rest_speed`` (or there is none), a plastic impact after
    which it rests against the stop (the core's momentum-keeping lock).  Resting, it is held against any push
    into the stop and none out of it: pulled away, it leaves (its friction, a bearing friction on the mass,
    holding it there while it can: the stop takes a push before any other hold of the mass).  The kinetic
    energy its impacts take is the ledger's ``<name>_impact_loss``.  Outputs ``<name>_force`` (its push on the
    mass, N, positive in the line's sense) and ``<name>_contact``.
    """

    position: object  # m, the mass's centre where it stops
    restitution_coefficient: object  # e
    rest_speed: object  # m/s, the slowest rebound
    mass: str = static("")
    section: str = static("")  # <stops>_lower or <stops>_upper

    side: ClassVar[float]  # +1 a lower stop (the mass pushed backwards into it), -1 an upper one
    end: ClassVar[str]  # the key that gives it
    switch_names: ClassVar[dict] = {"lock": "stop_reached", "unlock": "stop_left", "rebound": "stop_rebound"}
    observes_slip_peak: ClassVar[bool] = False
    holds_first: ClassVar[bool] = True

    @classmethod
    def from_spec(cls, spec) -> "AbstractEndStop":
        return cls(position=getattr(spec, cls.end), restitution_coefficient=spec.restitution,
                   rest_speed=spec.rest_speed, mass=spec.mass, section=f"{spec.name}_{cls.end}")

    @property
    def impact_state(self) -> str:
        return f"{self.section}_impact_loss"

    @property
    def ledger_kinds(self) -> dict:
        return {self.impact_state: "loss"}

    @property
    def summaries(self) -> dict:
        return {self.impact_state: "J"}

    @property
    def columns(self) -> dict:
        return {f"{self.section}_force": ("N", f"push of stop {self.section} on mass {self.mass}, positive in the "
                                               "line's sense"),
                f"{self.section}_contact": ("1", f"1 while mass {self.mass} rests against stop {self.section}")}

    def joins(self) -> tuple:
        return (self.mass, None)

    def weights(self) -> tuple:
        # its relative speed is the mass's speed away from the stop: forwards (slipping) is leaving it
        return ((self.mass, self.side),)

    def gap(self, x):
        return self.side * (x.angle(self.mass) - self.position)

    def angles(self) -> tuple:
        return (self.mass,)

    def restitution(self, x) -> tuple:
        return self.restitution_coefficient, self.rest_speed

    def states(self) -> dict:
        return {self.impact_state: 0.0}

    def ledger(self, x) -> dict:
        return {self.impact_state: x.state(self.impact_state)}

    def summary(self, x) -> dict:
        return {self.impact_state: x.state(self.impact_state)}

    def outputs(self, x) -> dict:
        # the coupling takes weight times its torque from the mass: the mass is pushed by minus that
        return {f"{self.section}_force": -self.side * x.coupling_torque(self.section),
                f"{self.section}_contact": (x.mode(self.section) == STUCK).astype(jnp.int8)}

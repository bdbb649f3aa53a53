"""A torsional spring and damper between two shafts, or a shaft and the ground (the housing)."""

from __future__ import annotations

from ..._pytree import static
from ..core.element import AbstractElement


class SpringDamper(AbstractElement):
    """tau = c (phi_rel - phi_rel0) + d w_rel, phi_rel = phi_b - phi_a and w_rel = w_b - w_a (Modelica's
    SpringDamper): it pulls shaft b back with tau and shaft a forward with it (a to the ground: only a).

    Its twist is a state of its own, integrated from w_rel (from its shafts' initial ``angle``s): a twist of
    1e-12 rad is not left to the difference of two angles of radians, whose round-off would freeze a spring
    ringing down to rest (its shafts' angles are outputs too).  Ledger: the strain energy
    1/2 c (phi_rel - phi_rel0)^2 (potential) and the damper's heat, the integral of d w_rel^2 (a loss, a
    state).  Outputs ``<name>_torque`` (tau), ``<name>_twist`` (phi_rel), ``<name>_twist_speed`` (w_rel).
    """

    stiffness: object  # c, N*m/rad
    damping: object  # d, N*m*s/rad
    unstretched_angle: object  # phi_rel0, rad
    initial_twist: object = 0.0  # phi_rel at t = 0, rad
    on_line: bool = static(False)  # between masses: a force (N), a stretch (m)
    driving: str | None = static(None)  # shaft a, None for the ground
    driven: str | None = static(None)  # shaft b, None for the ground
    section: str = static("")  # its name

    @classmethod
    def from_spec(cls, spec) -> "SpringDamper":
        return cls(**cls.fields_from(spec))

    @staticmethod
    def fields_from(spec) -> dict:
        a, b = (None if side == "ground" else side for side in spec.between)
        return dict(stiffness=spec.spring_rate, damping=spec.damping, unstretched_angle=spec.unstretched_angle,
                    initial_twist=spec.resolved("initial_twist"), on_line=spec.resolved("on_line"), driving=a,
                    driven=b, section=spec.name)

    @property
    def loss_state(self) -> str:
        return f"{self.section}_damping_loss"

    @property
    def twist_state(self) -> str:
        return f"{self.section}.twist"

    @property
    def ledger_kinds(self) -> dict:
        return {f"{self.section}_strain_energy": "potential", self.loss_state: "loss"}

    @property
    def output_names(self) -> tuple:
        """Its outputs' names: (what it passes, its twist, the twist's speed); a line's force and stretch."""
        name = self.section
        words = ("force", "stretch", "stretch_speed") if self.on_line else ("torque", "twist", "twist_speed")
        return tuple(f"{name}_{word}" for word in words)

    @property
    def columns(self) -> dict:
        body, units = ("mass", ("N", "m", "m/s")) if self.on_line else ("shaft", ("N*m", "rad", "rad/s"))
        a, b = (f"{body} {side}" if side else "the ground" for side in (self.driving, self.driven))
        passes, twist, speed = self.output_names
        what, where = ("force", "position") if self.on_line else ("torque", "angle")
        return {passes: (units[0], f"{what} {self.section} passes: it pulls {b} back with it, {a} forward"),
                twist: (units[1], f"{where} of {b} less that of {a}"),
                speed: (units[2], f"speed of {b} less that of {a}")}

    def angles(self) -> tuple:
        return tuple(side for side in (self.driving, self.driven) if side is not None)

    def twist(self, x):
        """phi_rel (rad): b's angle less a's (the ground's is 0), its own state."""
        return x.state(self.twist_state)

    def twist_speed(self, x):
        """w_rel (rad/s): b's speed less a's."""
        return self._of(x.speed, self.driven) - self._of(x.speed, self.driving)

    @staticmethod
    def _of(read, side):
        return 0.0 if side is None else read(side)

    def torque(self, x):
        return self.stiffness * (self.twist(x) - self.unstretched_angle) + self.damping * self.twist_speed(x)

    def strain(self, x):
        """The twist the spring is strained by (rad): the twist less the unstretched angle."""
        return self.twist(x) - self.unstretched_angle

    def torques(self, x) -> tuple:
        tau = self.torque(x)
        return tuple((side, sign * tau) for side, sign in ((self.driving, 1.0), (self.driven, -1.0))
                     if side is not None)

    def states(self) -> dict:
        return {self.twist_state: self.initial_twist, self.loss_state: 0.0}

    def loss_power(self, x):
        """W: the damper's heat, d w_rel^2."""
        return self.damping * self.twist_speed(x) ** 2

    def stored_strain(self, x):
        """The strain its spring stores energy by (rad)."""
        return self.strain(x)

    def rates(self, x) -> dict:
        return {self.twist_state: self.twist_speed(x), self.loss_state: self.loss_power(x)}

    def ledger(self, x) -> dict:
        return {f"{self.section}_strain_energy": 0.5 * self.stiffness * self.stored_strain(x) ** 2,
                self.loss_state: x.state(self.loss_state)}

    def outputs(self, x) -> dict:
        passes, twist, speed = self.output_names
        return {passes: self.torque(x), twist: self.twist(x), speed: self.twist_speed(x)}

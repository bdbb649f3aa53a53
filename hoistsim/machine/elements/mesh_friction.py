"""The friction of a lossy mesh's tooth flanks: what the gear loses, decided by which side drives."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from ..core.dynamics import slip_sign
from ..core.element import OPEN, STUCK
from ._slip_heat import AbstractSlipHeat


class MeshFriction(AbstractSlipHeat):
    """The mesh's losses as a friction torque of the pinion shaft against the gearbox, pressed by the tooth load.

    Modelica's LossyGear, in this machine's terms: with the tooth load T (the
    torque the pinion passes into the drum shaft) and the speed ratio r = z1/z2, the
    pinion loses, while the gear rolls,
    - (1/eta - 1) r |T| when the pinion drives (the power it gives the teeth is
      r T w / eta, the wheel receives r T w: efficiency eta), and
    - (1 - eta_b) r |T| when the wheel drives (it gives r T w, the pinion
      receives eta_b of it),
    the side that drives being the sign of the tooth load against the motion.
    At rest the gear is held (stuck) while the torque needed to hold it stays
    within what it would lose starting either way: a gear that cannot pass
    enough torque to move stays still, and a load too light to overhaul the
    mesh's losses does not run back.  Rolling, stopping and starting again are
    a coupling's slips, locks and breakaways, switched exactly by the core; the
    losses grow with the tooth load that the core solves for together with
    them (no efficiency factor applied after the fact, which would chatter).
    The gear pair itself stays one body with the drum geared to the pinion.
    Beside a brake or a pawl holding the drum, the gear held at rest yields
    the torque to them.
    """

    efficiency: object  # eta: the pinion drives
    backdrive_efficiency: object  # eta_b: the wheel drives
    ratio: object  # z1/z2: the drum's speed over the pinion's
    # its stage's name (the hoist's: mesh) and what its outputs' names begin with (mesh_torque, <stage>_mesh_torque),
    # as its spec says (from_spec)
    section: str = static("")
    prefix: str = static("")
    driving: str = static("")  # the input shaft, whose losses it is
    # the output shaft and every shaft geared beyond it: the tooth load is what the input passes into them
    beyond: tuple = static(())

    yields: ClassVar[bool] = True
    observes_slip_peak: ClassVar[bool] = False
    # where the tooth load changes sign while the gear rolls, the side that drives changes and with it the
    # law of the losses: a row of its own, and no step across it
    observation_kinds: ClassVar[tuple] = ("power_reversal",)
    crossings: ClassVar[tuple] = ("power_reversal",)

    @classmethod
    def from_spec(cls, spec, scenario) -> "MeshFriction":
        """A lossy gear stage's mesh: the input shaft's losses, pressed by what the shafts beyond take."""
        efficiency, backdrive = spec.efficiencies
        return cls(efficiency=efficiency, backdrive_efficiency=backdrive, ratio=spec.speed_ratio(), section=spec.name,
                   prefix=spec.mesh_prefix(), driving=spec.between[0], beyond=spec.beyond(scenario))

    @property
    def heat_state(self) -> str:
        return f"{self.prefix}_loss_energy"

    @property
    def summaries(self) -> dict:
        return {self.heat_state: "J"}

    @property
    def columns(self) -> dict:
        p, out = self.prefix, self.beyond[0]
        return {
            f"{p}_torque": ("N*m", f"tooth load: the torque the {self.driving} shaft passes to the {out} shaft, "
                                   f"at the {out} shaft"),
            f"{p}_loss_power": ("W", "power the tooth flanks' friction turns into heat"),
            f"{p}_heat": ("J", f"energy the mesh has lost so far (the summary's {self.heat_state} at the end)"),
            f"{p}_mode": ("1", f"0 the gear held at rest, 1 the {self.driving} shaft drives, 2 the {out} shaft "
                               "drives"),
        }

    @property
    def pressed_by(self) -> tuple:
        return self.beyond

    def joins(self) -> tuple:
        return (self.driving, None)

    def tooth_load(self, x):
        return x.torque_into(self.pressed_by)

    def _per_load(self, side):
        # N*m lost at the pinion per N*m of tooth load at the drum: side +1 the pinion drives
        return self.ratio * jnp.where(side > 0, 1.0 / self.efficiency - 1.0, 1.0 - self.backdrive_efficiency)

    def sliding_per_load(self, x, side):
        return self._per_load(side)

    def sliding_torque(self, x):
        return 0.0

    def capacity_toward(self, x, sign):
        # held at rest, the gear starts the way the pinion is pushed once it loses what rolling that way would
        load = self.tooth_load(x)
        return jnp.abs(load) * self._per_load(sign * load)

    def capacity(self, x):
        return jnp.maximum(self.capacity_toward(x, 1.0), self.capacity_toward(x, -1.0))

    def observations(self, x) -> dict:
        rolling = (x.mode(self.section) != STUCK) & (x.mode(self.section) != OPEN)
        return {"power_reversal": jnp.where(rolling, self.tooth_load(x), 1.0)}

    def summary(self, x) -> dict:
        return {self.heat_state: x.state(self.heat_state)}

    def outputs(self, x) -> dict:
        mode, p = x.mode(self.section), self.prefix
        rolling = (mode != STUCK) & (mode != OPEN)
        load = self.tooth_load(x)
        drives = load * slip_sign(mode) >= 0.0  # the load pushes the way the gear rolls: the pinion drives
        return {f"{p}_torque": load, f"{p}_loss_power": self.slip_power(x),
                f"{p}_heat": x.state(self.heat_state),
                f"{p}_mode": jnp.where(rolling, jnp.where(drives, 1, 2), 0).astype(jnp.int8)}

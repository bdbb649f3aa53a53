"""The friction of a lossy mesh's tooth flanks: what the gear loses, decided by which side drives."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..._pytree import static
from ._stage_mesh import AbstractStageMesh


class MeshFriction(AbstractStageMesh):
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

    loss_power_text: ClassVar[str] = "power the tooth flanks' friction turns into heat"
    losing_part: ClassVar[str] = "the mesh"

    @classmethod
    def from_spec(cls, spec) -> "MeshFriction":
        """A lossy gear stage's mesh: the input shaft's losses, pressed by what the shafts beyond take."""
        efficiency, backdrive = spec.efficiencies
        return cls(efficiency=efficiency, backdrive_efficiency=backdrive, ratio=spec.resolved("speed_ratio"),
                   section=spec.name, prefix=f"{spec.name}_mesh", driving=spec.between[0],
                   beyond=spec.resolved("beyond"))

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

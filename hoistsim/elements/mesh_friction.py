"""The friction of a lossy mesh's tooth flanks: what the gear loses, decided by which side drives."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..core.dynamics import slip_sign
from ..core.element import OPEN, STUCK
from ..core.panel import Panel, Phase, SummaryPanel, Trace
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

    section: ClassVar[str] = "mesh"
    heat_state: ClassVar[str] = "mesh_loss_energy"
    pressed_by: ClassVar[str] = "drum"  # the tooth load: what the pinion passes into the drum shaft
    yields: ClassVar[bool] = True
    observes_slip_peak: ClassVar[bool] = False
    # where the tooth load changes sign while the gear rolls, the side that drives changes and with it the
    # law of the losses: a row of its own, and no step across it
    observation_kinds: ClassVar[tuple] = ("power_reversal",)
    crossings: ClassVar[tuple] = ("power_reversal",)
    summaries: ClassVar[dict] = {"mesh_loss_energy": "J"}
    ledger_kinds: ClassVar[dict] = {"mesh_loss_energy": "loss"}
    columns: ClassVar[dict] = {
        "mesh_torque": ("N*m", "tooth load: the torque the pinion passes to the wheel, at the drum shaft"),
        "mesh_loss_power": ("W", "power the tooth flanks' friction turns into heat"),
        "mesh_heat": ("J", "energy the mesh has lost so far (the summary's mesh_loss_energy at the end)"),
        "mesh_mode": ("1", "0 the gear held at rest, 1 the pinion drives the wheel, 2 the wheel drives the pinion"),
    }
    panels: ClassVar[tuple] = (Panel("mesh", "mesh [N*m]\n(tooth load at the drum)", 45, (
        Trace("tooth load", "mesh_torque"),), zero_line=True, height=0.8),)
    shading: ClassVar[tuple] = (Phase("wheel drives the pinion", "mesh_mode", 2, "#b2182b", hatch="..."),)
    summary_panels: ClassVar[tuple] = (SummaryPanel("mesh_loss_energy", "mesh losses [kJ]", 45, scale=1e-3),)

    @classmethod
    def from_spec(cls, spec, scenario) -> "MeshFriction":
        efficiency, backdrive = spec.efficiencies
        return cls(efficiency=efficiency, backdrive_efficiency=backdrive,
                   ratio=float(spec.pinion_teeth) / float(spec.wheel_teeth))

    @classmethod
    def headline(cls, summary: dict) -> str | None:
        return f"mesh losses {float(summary['mesh_loss_energy']) / 1000:.2f} kJ"

    def joins(self) -> tuple:
        return ("pinion", None)

    def _per_load(self, side):
        # N*m lost at the pinion per N*m of tooth load at the drum: side +1 the pinion drives
        return self.ratio * jnp.where(side > 0, 1.0 / self.efficiency - 1.0, 1.0 - self.backdrive_efficiency)

    def sliding_per_load(self, x, side):
        return self._per_load(side)

    def sliding_torque(self, x):
        return 0.0

    def capacity_toward(self, x, sign):
        # held at rest, the gear starts the way the pinion is pushed once it loses what rolling that way would
        load = x.torque_into("drum")
        return jnp.abs(load) * self._per_load(sign * load)

    def capacity(self, x):
        return jnp.maximum(self.capacity_toward(x, 1.0), self.capacity_toward(x, -1.0))

    def observations(self, x) -> dict:
        rolling = (x.mode("mesh") != STUCK) & (x.mode("mesh") != OPEN)
        return {"power_reversal": jnp.where(rolling, x.torque_into("drum"), 1.0)}

    def summary(self, x) -> dict:
        return {"mesh_loss_energy": x.state("mesh_loss_energy")}

    def outputs(self, x) -> dict:
        mode = x.mode("mesh")
        rolling = (mode != STUCK) & (mode != OPEN)
        load = x.torque_into("drum")
        drives = load * slip_sign(mode) >= 0.0  # the load pushes the way the gear rolls: the pinion drives
        return {"mesh_torque": load, "mesh_loss_power": self.slip_power(x),
                "mesh_heat": x.state("mesh_loss_energy"),
                "mesh_mode": jnp.where(rolling, jnp.where(drives, 1, 2), 0).astype(jnp.int8)}

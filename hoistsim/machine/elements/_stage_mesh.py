"""What a lossy gear stage's losses share, whatever their law (a constant efficiency, Modelica's loss table): a
friction of the input shaft against the gearbox, pressed by the tooth load, its outputs and its heat."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from ..core.dynamics import slip_sign
from ..core.element import OPEN, STUCK
from ._slip_heat import AbstractSlipHeat


class AbstractStageMesh(AbstractSlipHeat):
    """A stage's losses as a coupling of its input shaft (``driving``) to the ground, pressed by what the shafts
    beyond it take (``beyond``: its output shaft, then every shaft geared beyond it), its outputs' names beginning
    with ``prefix``.  Held at rest beside other holds of its shafts, it yields the torque to them.  Where the
    torque its teeth carry (``carried``) changes sign while it rolls, the side that drives changes and with it the
    law of its losses: a row of its own (``power_reversal``), and no step across it.  A subclass gives its law
    (``sliding_per_load``, ``capacity_toward``, ...) and the fields ``section``, ``prefix``, ``driving``,
    ``beyond``."""

    loss_power_text: ClassVar[str]  # what its loss power is, in a column's words
    losing_part: ClassVar[str]  # what loses it: "the mesh", "the stage"

    yields: ClassVar[bool] = True
    observes_slip_peak: ClassVar[bool] = False
    observation_kinds: ClassVar[tuple] = ("power_reversal",)
    crossings: ClassVar[tuple] = ("power_reversal",)

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
            f"{p}_loss_power": ("W", self.loss_power_text),
            f"{p}_heat": ("J", f"energy {self.losing_part} has lost so far (the summary's {self.heat_state} at the "
                               "end)"),
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

    def carried(self, x, mode):
        """The torque its teeth carry, at the output, pushing the way the gear rolls where positive times it: the
        tooth load (and what else the law adds to it)."""
        return self.tooth_load(x)

    def capacity(self, x):
        return jnp.maximum(self.capacity_toward(x, 1.0), self.capacity_toward(x, -1.0))

    def observations(self, x) -> dict:
        mode = x.mode(self.section)
        rolling = (mode != STUCK) & (mode != OPEN)
        return {"power_reversal": jnp.where(rolling, self.carried(x, mode), 1.0)}

    def summary(self, x) -> dict:
        return {self.heat_state: x.state(self.heat_state)}

    def outputs(self, x) -> dict:
        mode, p = x.mode(self.section), self.prefix
        rolling = (mode != STUCK) & (mode != OPEN)
        drives = self.carried(x, mode) * slip_sign(mode) >= 0.0  # the teeth push the way it rolls: the input drives
        return {f"{p}_torque": self.tooth_load(x), f"{p}_loss_power": self.slip_power(x),
                f"{p}_heat": x.state(self.heat_state),
                f"{p}_mode": jnp.where(rolling, jnp.where(drives, 1, 2), 0).astype(jnp.int8)}

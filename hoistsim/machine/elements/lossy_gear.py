"""A gear stage's losses from Modelica's lossTable: mesh efficiencies and bearing friction that depend on the speed
and on which side drives."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp
import numpy as np

from ..._pytree import static
from ..core.dynamics import slip_sign
from ._stage_mesh import AbstractStageMesh
from ._slip_table import along_slip, slip_knots


class LossyGear(AbstractStageMesh):
    """Modelica's LossyGear with its lossTable rows [|w_a|, eta_mf1, eta_mf2, tau_bf1, tau_bf2]: the stage's
    losses as a friction torque of its input shaft against the gearbox, pressed by the tooth load.

    Modelica's equations, -flange_b.tau = i eta_mf (flange_a.tau - tau_bf_a) - tau_bf_b, split the resultant
    bearing frictions of the table into one on the input side, tau_bf_a = (tau_bf1 - tau_bf2) /
    (eta_mf1 - 1/eta_mf2), and one on the output side, tau_bf_b / i = tau_bf1 - eta_mf1 tau_bf_a (at the
    input; half each where both efficiencies are 1).  Rolling, what the input loses is then
        tau_bf_a + tau_bf_b / i + (1/eta_mf1 - 1) |Q|   when the input drives (Q pushes the way it rolls),
        tau_bf_a + tau_bf_b / i + (1 - eta_mf2) |Q|     when the output drives,
    Q the torque the teeth carry, at the input: what the output shaft and every shaft beyond it take (the
    tooth load T at the output, times r = 1/i) plus the output side's bearing friction, tau_bf_b / i, the way it
    rolls.  This is Modelica's tauLoss written in the tooth load instead of flange_a.tau (quadrants 1 to 4:
    the same losses, the same switch between them where flange_a.tau -+ tau_bf_a changes sign, that is where Q
    does), so the core solves it with the tooth load as it does the hoist's mesh (no efficiency factor applied
    after the fact).  The table is read at the size of the input's speed, linear between rows, flat beyond
    the last (Modelica extrapolates the last two rows, which could take an efficiency out of (0, 1]); its
    knots are kinks no step straddles.

    At rest the gear is held while the torque that holds it stays within what it would lose starting that way,
    with the first row's numbers: Modelica's startForward (sa > tauLossMax_p) and startBackward
    (sa < tauLossMin_m), whose thresholds, written in flange_a.tau, are these losses at the tooth load that
    holds it.  Held beside other holds of its shafts (a bearing friction), it yields the torque to them, as the
    hoist's mesh does.  Its threshold differs with the way it is pushed, so its margin to breakaway jumps where
    the holding torque changes sign, and a machine at rest has nothing to limit the step: each way's margin
    has a valley guard of its own (``margin_each_way``), so that no step hides a breakaway that comes and goes
    within it.  Where Q changes sign while it rolls the law changes: a row there (``power_reversal``).
    """

    speeds: object  # rad/s, the table's (|w_a|)
    input_efficiencies: object  # eta_mf1: the input drives
    output_efficiencies: object  # eta_mf2: the output drives
    input_bearing_torques: object  # N*m, tau_bf1 (at the input): the input drives
    output_bearing_torques: object  # N*m, tau_bf2: the output drives
    ratio: object  # r: the output's speed over the input's (1/i)
    section: str = static("")
    prefix: str = static("")  # what its outputs' names begin with: <stage>_mesh
    driving: str = static("")  # the input shaft, whose losses they are
    # the output shaft and every shaft geared beyond it: the tooth load is what the input passes into them
    beyond: tuple = static(())
    varies: bool = static(False)  # more than one row: the table's knots are kinks

    loss_power_text: ClassVar[str] = "power the mesh and the bearings turn into heat"
    losing_part: ClassVar[str] = "the stage"
    margin_each_way: ClassVar[bool] = True

    @classmethod
    def from_spec(cls, spec) -> "LossyGear":
        """A stage's loss table: the input shaft's losses, pressed by what the shafts beyond take."""
        table = np.asarray(spec.loss_table, dtype=float)
        return cls(speeds=table[:, 0], input_efficiencies=table[:, 1], output_efficiencies=table[:, 2],
                   input_bearing_torques=table[:, 3], output_bearing_torques=table[:, 4],
                   ratio=spec.resolved("speed_ratio"), section=spec.name, prefix=f"{spec.name}_mesh",
                   driving=spec.between[0], beyond=spec.resolved("beyond"), varies=table.shape[0] > 1)

    # ------------------------------------------------------------------ the table's law

    def _row(self, x, at_rest: bool):
        """(eta_mf1, eta_mf2, tau_bf1, tau_bf2) at the input's speed, or at rest (the first row)."""
        columns = (self.input_efficiencies, self.output_efficiencies, self.input_bearing_torques,
                   self.output_bearing_torques)
        if at_rest:
            return tuple(c[0] for c in columns)
        return tuple(along_slip(x, self.section, self.speeds, c) for c in columns)

    def _law(self, x, at_rest: bool = False):
        """(per N*m of tooth load at the output: lost at the input when it drives, when the output drives;
        the bearings' friction at the input; the output side's bearing friction at the output)."""
        eta1, eta2, bf1, bf2 = self._row(x, at_rest)
        across = eta1 - 1.0 / eta2  # 0 only for an ideal mesh (both 1): Modelica then splits the friction in half
        ideal = across == 0.0
        input_side = jnp.where(ideal, 0.5 * bf1, (bf1 - bf2) / jnp.where(ideal, 1.0, across))
        output_side = bf1 - eta1 * input_side  # tau_bf_b / i
        return (self.ratio * (1.0 / eta1 - 1.0), self.ratio * (1.0 - eta2), input_side + output_side,
                output_side / self.ratio)

    @staticmethod
    def _per_load(law, side):
        return jnp.where(side > 0, law[0], law[1])

    # ------------------------------------------------------------------ the coupling

    def sliding_torque(self, x):
        return self._law(x)[2]

    def sliding_per_load(self, x, side):
        return self._per_load(self._law(x), side)

    def pressed_beside(self, x):
        return self._law(x)[3]

    def capacity_toward(self, x, sign):
        # held at rest, it starts the way the input is pushed once the torque holding it exceeds what rolling
        # that way would lose, the teeth carrying the tooth load and the output side's bearing friction
        law = self._law(x, at_rest=True)
        carried = self.tooth_load(x) + sign * law[3]
        return law[2] + jnp.abs(carried) * self._per_load(law, sign * carried)

    def kink_names(self) -> tuple:
        return ("loss_knots",) if self.varies else ()

    def kinks(self, x) -> dict:
        return {"loss_knots": slip_knots(x, self.section, self.speeds)} if self.varies else {}

    def carried(self, x, mode):
        """Q: the tooth load and the output side's bearing friction the way it rolls, at the output."""
        return self.tooth_load(x) + slip_sign(mode) * self._law(x)[3]

"""An ideal planetary set: sun, carrier and ring held by Willis's relation (Modelica's IdealPlanetary)."""

from __future__ import annotations

from ..._pytree import static
from ._linkage import AbstractLinkage


class Planetary(AbstractLinkage):
    """(1 + r) w_carrier = w_sun + r w_ring, r the ring's teeth over the sun's (> 1): the sun, the ring and
    the carrier weigh 1, r and -(1 + r).  Its torques stand as 1 : r : -(1 + r) (sun : ring : carrier),
    the carrier's balancing the other two.  Outputs ``<name>_sun_torque``, ``<name>_carrier_torque``,
    ``<name>_ring_torque``: the torque each shaft drives the set with (Modelica's sun.tau, carrier.tau,
    ring.tau)."""

    ratio: object  # r = z_ring / z_sun
    sun: str = static("")
    carrier: str = static("")
    ring: str = static("")
    section: str = static("")  # its name

    @classmethod
    def from_spec(cls, spec) -> "Planetary":
        return cls(ratio=spec.ratio, sun=spec.sun, carrier=spec.carrier, ring=spec.ring, section=spec.name)

    def members(self) -> tuple:
        return (("sun", self.sun, 1.0), ("carrier", self.carrier, -(1.0 + self.ratio)),
                ("ring", self.ring, self.ratio))

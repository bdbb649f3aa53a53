"""A buffer under the hoisted load at the end of its travel (the load's ``buffer``)."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp

from .elasto_gap import ElastoGap

# EN 13001-2's phi7 for a buffer whose characteristic xi_b (the energy it takes over its peak force times its
# stroke) is 0.5, a linear spring's: 1.25 for 0 <= xi_b <= 0.5 (1.25 + 0.7 (xi_b - 0.5) above)
PHI7_LINEAR_BUFFER = 1.25
# The load is at the buffer's top within this (m) where its contact is located: the root's own resolution, either
# side of the top (the pass that meets the buffer ends there, and the load's speed is read at that instant).
AT_THE_TOP = 1e-9


class LoadBuffer(ElastoGap):
    """The elasto-gap between the ground and the load (the body ``load``, on its elastic rope): its twist is the
    load's height above its start, and it touches once the load is ``clearance`` below it, pushing the load up
    with k_b delta + min(k_b delta, d_b delta') (delta its compression), never pulling.  Its peak push is a row
    (``buffer_force_peak``).

    Outputs ``buffer_force`` (its push up on the load, N), ``buffer_compression`` (m) and ``buffer_contact``;
    events ``contact`` and ``separation``.  Summaries: the peak force and compression, the load's speed where it
    first meets the buffer, and beside them the standard's design force: EN 13001-2's phi7 (1.25, a linear
    buffer) times the rigid-body peak force of the load arriving at that speed on the buffer's spring under its
    own weight, M g + sqrt((M g)^2 + k_b M v^2).
    """

    load_mass: object = 0.0  # M, kg
    gravity: object = 0.0  # g, m/s^2

    observation_kinds: ClassVar[tuple] = (*ElastoGap.observation_kinds, "buffer_force_peak")
    summaries: ClassVar[dict] = {"peak_buffer_force": "N", "peak_buffer_compression": "m",
                                 "buffer_impact_speed": "m/s", "buffer_force_standard": "N"}

    @classmethod
    def from_spec(cls, spec) -> "LoadBuffer":
        buffer = spec.buffer
        return cls(stiffness=buffer.stiffness, damping=buffer.damping, unstretched_angle=-buffer.clearance,
                   on_line=True, driving=None, driven="load", section="buffer", damped=buffer.damping > 0.0,
                   load_mass=spec.mass, gravity=spec.resolved("gravity"))

    @property
    def columns(self) -> dict:
        return {"buffer_force": ("N", "the buffer's push up on the load (0 apart)"),
                "buffer_compression": ("m", "how far the load has pressed the buffer in"),
                "buffer_contact": ("1", "1 while the load presses the buffer")}

    def angles(self) -> tuple:
        # its twist, the load's height, is a state of its own: the load's position is no angle to write
        return ()

    def push(self, x):
        """The buffer's push up on the load (N, >= 0)."""
        return -self.torque(x)

    def observations(self, x) -> dict:
        # the push's rate while touching, falling through zero at its peak (a row, so the summary's peak is exact):
        # 2 k delta' while the damping is limited to the spring, k delta' + d delta'' after
        compressing = -self.twist_speed(x)
        limited = self.stiffness * self.stored_strain(x) - self.damping * self.twist_speed(x) > 0.0
        rate = jnp.where(limited, 2.0 * self.stiffness * compressing,
                         self.stiffness * compressing - self.damping * x.acceleration("load"))
        return {**super().observations(x), "buffer_force_peak": jnp.where(self.pushing(x) > 0.0, rate, 1.0)}

    def extremes(self, x) -> dict:
        touching = self.strain(x) <= AT_THE_TOP
        speed = -x.speed("load")  # coming down
        weight = self.load_mass * self.gravity
        rigid = weight + jnp.sqrt(weight**2 + self.stiffness * self.load_mass * speed**2)
        return {"peak_buffer_force": ("max", self.push(x)),
                "peak_buffer_compression": ("max", -self.stored_strain(x)),
                "buffer_impact_speed": ("first_value", (touching, speed)),
                "buffer_force_standard": ("first_value", (touching, PHI7_LINEAR_BUFFER * rigid))}

    def outputs(self, x) -> dict:
        return {"buffer_force": self.push(x), "buffer_compression": -self.stored_strain(x),
                "buffer_contact": (self.pushing(x) > 0.0).astype(jnp.int8)}

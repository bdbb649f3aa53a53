"""A friction clutch of a drawn drivetrain: between two shafts, or a shaft and the ground (a brake)."""

from __future__ import annotations

from typing import ClassVar

import jax.numpy as jnp
import numpy as np

from ..._pytree import static
from ..core.element import STUCK
from ._signal import harmonics_at, signal_fields
from ._slip_heat import AbstractSlipHeat


class FrictionClutch(AbstractSlipHeat):
    """Faces pressed by a force F(t), a time signal: static capacity mu_s c F and sliding torque mu_k c F,
    c = effective radius times surfaces (Modelica's ``cgeo``), nothing where F <= 0.

    A force given as a table is open over any segment where it stays at or below zero (where it
    crosses zero between two rows is a segment boundary, like the rows); a force in
    harmonics may cross zero anywhere, so its sign is watched: the crossing is found like a switch
    (events ``disengage`` falling, ``engage`` rising) and no step straddles the kink of max(F, 0).  Its
    heat of slip is a state and a loss of the ledger; its events carry its name.
    """

    static_friction: object
    kinetic_friction: object
    torque_per_newton: object  # m: effective radius times surfaces
    force_times: object  # s
    force_values: object  # N
    force_amplitudes: object  # N
    force_frequencies: object  # Hz
    force_phases: object  # rad
    driving: str = static("")  # shaft a
    driven: str | None = static(None)  # shaft b, None for the ground
    section: str = static("")  # the clutch's name in drivetrain.clutches
    in_harmonics: bool = static(False)

    observation_kinds: ClassVar[tuple] = ("clutch_force",)
    crossings: ClassVar[tuple] = ("clutch_force",)
    crossing_events: ClassVar[dict] = {"clutch_force": ("engage", "disengage")}

    # A drawn part's builder, called by Drivetrain.from_spec with the clutch's name: not yet the registry's
    # (spec, scenario), which it takes once the registry builds drawn parts too.
    @classmethod
    def from_spec(cls, name: str, spec) -> "FrictionClutch":
        a, b = spec.between
        return cls(static_friction=spec.static_friction, kinetic_friction=spec.kinetic_friction,
                   torque_per_newton=spec.torque_per_newton, **signal_fields(spec.force, "force"), driving=a,
                   driven=None if b == "ground" else b, section=name, in_harmonics=spec.force.has_harmonics)

    @property
    def heat_state(self) -> str:
        return f"{self.section}_energy"

    @property
    def summaries(self) -> dict:
        return {f"{self.section}_lockup_time": "s", f"{self.section}_slip_energy": "J"}

    @property
    def columns(self) -> dict:
        name, b = self.section, self.driven or "the ground"
        return {f"{name}_torque": ("N*m", f"torque clutch {name} passes from {self.driving} to {b}"),
                f"{name}_slip": ("rad/s", f"speed of {self.driving} less that of {b}"),
                f"{name}_locked": ("1", f"1 while clutch {name} sticks"),
                f"{name}_force": ("N", f"force pressing clutch {name}"),
                f"{name}_energy": ("J", f"energy dissipated in clutch {name} so far"),
                f"{name}_mode": ("1", "0 locked, 1 slipping forwards, 2 slipping backwards, 3 open")}

    def joins(self) -> tuple:
        return (self.driving, self.driven)

    def tables(self) -> dict:
        return {f"{self.section}.force": ("force_times", "force_values")}

    def force(self, x):
        return x.table(f"{self.section}.force") + harmonics_at(x.t, self.force_amplitudes, self.force_frequencies,
                                                               self.force_phases)

    def pressing(self, x):
        """The force that presses the faces: F, or 0 where F <= 0 (the clutch is open)."""
        return jnp.maximum(self.force(x), 0.0)

    def capacity(self, x):
        return self.static_friction * self.torque_per_newton * self.pressing(x)

    def sliding_torque(self, x):
        return self.kinetic_friction * self.torque_per_newton * self.pressing(x)

    def boundaries(self) -> tuple:
        """Where the force table crosses zero between two knots: a segment boundary, like the knots, so
        that the kink of max(F, 0) is never inside a segment (one per interval, at its start where the
        force does not cross: the count is the table's structure, the times its numbers)."""
        t, v = np.asarray(self.force_times, float), np.asarray(self.force_values, float)  # on the host, as knots
        if t.shape[-1] < 2:
            return ()
        t0, t1, v0, v1 = t[..., :-1], t[..., 1:], v[..., :-1], v[..., 1:]
        crosses = (v0 * v1 < 0.0) & (t1 > t0)
        at = np.where(crosses, t0 + v0 / np.where(crosses, v0 - v1, 1.0) * (t1 - t0), t0)
        return tuple(at[..., i] for i in range(at.shape[-1]))

    def is_open(self, segment):
        if self.in_harmonics:
            return False
        # the force's sign holds over a segment (its zeros are boundaries): the middle's decides
        value, slope = segment.lines[f"{self.section}.force"]
        return value + slope * 0.5 * (segment.end - segment.start) <= 0.0

    def observes(self, kind: str) -> bool:
        return self.in_harmonics

    def observations(self, x) -> dict:
        if not self.in_harmonics:
            return {}
        return {"clutch_force": self.force(x)}

    def extremes(self, x) -> dict:
        return {f"{self.section}_lockup_time": ("first", x.mode(self.section) == STUCK)}

    def summary(self, x) -> dict:
        return {f"{self.section}_slip_energy": x.state(self.heat_state)}

    def outputs(self, x) -> dict:
        name, mode = self.section, x.mode(self.section)
        return {f"{name}_torque": x.coupling_torque(name), f"{name}_slip": x.relative_speed(name),
                f"{name}_locked": (mode == STUCK).astype(jnp.int8), f"{name}_force": self.force(x),
                f"{name}_energy": x.state(self.heat_state), f"{name}_mode": mode.astype(jnp.int8)}

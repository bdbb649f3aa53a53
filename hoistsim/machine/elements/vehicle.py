"""A vehicle's driving resistances on the mass that is its body (Modelica's Translational.Components.Vehicle)."""

from __future__ import annotations

import jax.numpy as jnp

from ..._pytree import static
from ..core.element import AbstractElement
from ._knots import knots_passed
from ._signal import harmonics_step, signal_at, signal_fields, signal_tables


class Vehicle(AbstractElement):
    """Rolling resistance, the air's drag and the grade on a mass, each a force (N, positive in the line's sense):

    - rolling: -Cr W cos(alpha) sign(v), linear in v below the regularization speed v0 (Modelica's Linear
      regularization), whose kinks at v = -v0 and v0 no step straddles; its heat a loss of the ledger;
    - drag: -Cd A rho (v - v_wind) |v - v_wind| / 2; its work a term of the ledger (a wind may push);
    - grade: -W sin(alpha); its work a term of the ledger (the grade is a signal of time: no potential);

    alpha = atan(inclination(t)), W the mass's weight.  A part without drag or grade has no such term.
    """

    weight: object  # W = m g, N
    rolling_resistance: object  # Cr
    regularization: object  # v0, m/s
    drag_factor: object = 0.0  # Cd A rho / 2, kg/m
    wind: object = 0.0  # m/s
    inclination_times: object = None  # s (None: level)
    inclination_values: object = None
    inclination_amplitudes: object = None
    inclination_frequencies: object = None
    inclination_phases: object = None
    inclination_envelope_times: object = None
    inclination_envelope_values: object = None
    mass: str = static("")
    name: str = static("")  # the vehicle's: its outputs' (it may be its mass's)
    section: str = static("")  # <name>_resistances: the machine's name of the part, apart from its mass's
    dragged: bool = static(False)
    inclined: bool = static(False)

    @classmethod
    def from_spec(cls, spec) -> "Vehicle":
        drag = spec.drag
        air = {} if drag is None else {"drag_factor": drag.coefficient * drag.area * drag.air_density / 2.0,
                                       "wind": drag.wind}
        grade = {} if spec.inclination is None else signal_fields(spec.inclination, "inclination")
        return cls(weight=spec.resolved("weight"), rolling_resistance=spec.rolling_resistance,
                   regularization=spec.rolling_regularization, **air, **grade, mass=spec.mass, name=spec.name,
                   section=f"{spec.name}_resistances",
                   dragged=drag is not None, inclined=spec.inclination is not None)

    @property
    def columns(self) -> dict:
        name, mass = self.name, self.mass
        out = {f"{name}_rolling_force": ("N", f"rolling resistance of vehicle {name} on mass {mass}")}
        if self.dragged:
            out[f"{name}_drag_force"] = ("N", f"the air's drag on vehicle {name} (mass {mass})")
        if self.inclined:
            out[f"{name}_grade_force"] = ("N", f"gravity along the grade on vehicle {name} (mass {mass})")
        return out

    @property
    def ledger_kinds(self) -> dict:
        name = self.name
        return {f"{name}_rolling_loss": "loss", **({f"{name}_drag_work": "work"} if self.dragged else {}),
                **({f"{name}_grade_work": "work"} if self.inclined else {})}

    def tables(self) -> dict:
        return signal_tables(self, "inclination") if self.inclined else {}

    def longest_step(self):
        # a grade swinging in time swings the force a held vehicle's friction carries
        return harmonics_step(self, "inclination")

    def _angle_cos_sin(self, x):
        if not self.inclined:
            return 1.0, 0.0
        alpha = jnp.arctan(signal_at(self, x, "inclination"))
        return jnp.cos(alpha), jnp.sin(alpha)

    def forces(self, x) -> dict:
        """Each resistance's force on the mass (N), by its column's name."""
        v = x.speed(self.mass)
        cos, sin = self._angle_cos_sin(x)
        rolling = -self.rolling_resistance * self.weight * cos * jnp.clip(v / self.regularization, -1.0, 1.0)
        out = {f"{self.name}_rolling_force": rolling}
        if self.dragged:
            relative = v - self.wind
            out[f"{self.name}_drag_force"] = -self.drag_factor * relative * jnp.abs(relative)
        if self.inclined:
            out[f"{self.name}_grade_force"] = -self.weight * sin
        return out

    def torques(self, x) -> tuple:
        return ((self.mass, sum(self.forces(x).values())),)

    def states(self) -> dict:
        return dict.fromkeys(self.ledger_kinds, 0.0)

    def rates(self, x) -> dict:
        v, forces, name = x.speed(self.mass), self.forces(x), self.name
        out = {f"{name}_rolling_loss": -forces[f"{name}_rolling_force"] * v}
        if self.dragged:
            out[f"{name}_drag_work"] = forces[f"{name}_drag_force"] * v
        if self.inclined:
            out[f"{name}_grade_work"] = forces[f"{name}_grade_force"] * v
        return out

    def ledger(self, x) -> dict:
        return {term: x.state(term) for term in self.ledger_kinds}

    def kink_names(self) -> tuple:
        return ("rolling_regularization",)

    def kinks(self, x) -> dict:
        # the rolling resistance's kinks, where the speed passes -v0 and v0: no step straddles them
        knots = jnp.stack([-self.regularization, self.regularization])
        return {"rolling_regularization": knots_passed(x.speed(self.mass), knots)}

    def outputs(self, x) -> dict:
        return self.forces(x)

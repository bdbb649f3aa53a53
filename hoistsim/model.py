"""The reduced model: every mass and force brought to the two clutch shafts.

Side a is the motor shaft; side b the clutch output (pinion) shaft.  Masses are
reduced by equal kinetic energy and forces by equal power (physics.md):

    J_a = J_motor + J_clutch,driving
    J_b = J_clutch,driven + J_pinion + (J_wheel + I_drum + M R^2) / tau^2
    T_L = M g R / tau

The numbers live in :class:`Drivetrain`, a pytree dataclass, so the same object
is a set of traced inputs inside the compiled solver and a set of plain floats
for the closed-form solution.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._pytree import pytree_dataclass
from .components import ConeClutch, Drum, GearPair, HangingLoad, LinearMotor
from .scenario import Scenario

# Clutch modes.  Integers so that they can be traced and stored.
LOCKED, SLIP_FORWARD, SLIP_BACKWARD, OPEN = 0, 1, 2, 3

# A clutch exactly at its static limit holds (|T_c| <= T_s).  Computed in floating
# point, a torque that equals the capacity wanders by a few ulps either side of
# it, and a steady lift at the limit would break away on round-off.  The capacity
# is therefore taken 1e-12 larger (relative) for every sticking decision and
# breakaway guard; that moves a genuine breakaway by ~1e-12 of its torque ramp's
# time scale, far inside any solver tolerance.
STICK_TOLERANCE = 1e-12

# A slip below this fraction of the no-load speed is no slip at all when the mode
# is decided at a boundary (and at t = 0).  Without it a slip of 1e-312 rad/s, a
# subnormal number that XLA flushes to zero but numpy keeps, would decide between
# sticking and slipping.  4 eps: the round-off of a speed of order omega0.
SLIP_RESOLUTION = 4 * 2.220446049250313e-16

MODE_NAMES = {LOCKED: "locked", SLIP_FORWARD: "slipping+", SLIP_BACKWARD: "slipping-", OPEN: "open"}


@dataclass(frozen=True)
class Machine:
    """The hoist's elements, built from a scenario's geometry."""

    motor: LinearMotor
    clutch: ConeClutch
    gears: GearPair
    drum: Drum
    load: HangingLoad
    driving_inertia: float = 0.0
    driven_inertia: float = 0.0

    @classmethod
    def from_scenario(cls, scenario: Scenario) -> "Machine":
        m, c, g = scenario.motor, scenario.clutch, scenario.gears
        return cls(
            motor=LinearMotor(m.stall_torque, m.no_load_speed, m.moment_of_inertia),
            clutch=ConeClutch(c.inner_radius, c.outer_radius, c.half_angle, c.static_friction,
                              c.kinetic_friction, c.surfaces, c.mean_radius),
            gears=GearPair(g.pinion_teeth, g.wheel_teeth, g.module, g.pressure_angle,
                           g.pinion_inertia, g.wheel_inertia),
            drum=Drum(scenario.drum.diameter, scenario.drum.inertia),
            load=HangingLoad(scenario.load.mass, scenario.gravity),
            driving_inertia=c.driving_inertia,
            driven_inertia=c.driven_inertia,
        )

    def reduced(self) -> "Drivetrain":
        tau = self.gears.ratio
        R = self.drum.rope_radius
        drum_side = self.gears.wheel_inertia + self.drum.inertia + self.load.mass * R**2
        return Drivetrain(
            motor_inertia=self.motor.inertia + self.driving_inertia,
            output_inertia=self.driven_inertia + self.gears.pinion_inertia + drum_side / tau**2,
            stall_torque=self.motor.stall_torque,
            no_load_speed=self.motor.no_load_speed,
            load_torque=self.load.weight * R / tau,
            clutch_constant=self.clutch.torque_per_newton,
            static_friction=self.clutch.static_friction,
            kinetic_friction=self.clutch.kinetic_friction,
            ratio=tau,
            rope_radius=R,
            load_weight=self.load.weight,
        )


@pytree_dataclass
class Drivetrain:
    """The two-shaft reduced model (SI).  Fields may be floats or (traced) arrays."""

    motor_inertia: float  # J_a, kg*m^2
    output_inertia: float  # J_b, kg*m^2, reduced to the pinion shaft
    stall_torque: float  # C0, N*m
    no_load_speed: float  # omega0, rad/s
    load_torque: float  # T_L, N*m on the pinion shaft
    clutch_constant: float  # c = n r_m / sin(beta), m
    static_friction: float
    kinetic_friction: float
    ratio: float  # tau, pinion speed / drum speed
    rope_radius: float  # R, m
    load_weight: float  # M g, N

    def motor_torque(self, motor_speed):
        return self.stall_torque * (1.0 - motor_speed / self.no_load_speed)

    def static_capacity(self, engagement_force):
        return self.static_friction * self.clutch_constant * engagement_force

    def kinetic_torque(self, engagement_force):
        return self.kinetic_friction * self.clutch_constant * engagement_force

    def load_speed(self, output_speed):
        """Rope speed (m/s, up positive) for a pinion speed (rad/s)."""
        return self.rope_radius * output_speed / self.ratio

    def kinetic_energy(self, motor_speed, output_speed):
        return 0.5 * self.motor_inertia * motor_speed**2 + 0.5 * self.output_inertia * output_speed**2


def initial_speeds(scenario: Scenario, drivetrain: "Drivetrain") -> tuple[float, float]:
    """Motor and pinion-shaft speeds at t = 0 (rad/s).

    ``initial.steady_lift`` puts both at the speed where the motor torque equals
    the load torque, omega0 (1 - T_L/C0): the hoist lifting at constant speed.
    """
    if scenario.initial.steady_lift:
        speed = drivetrain.no_load_speed * (1.0 - drivetrain.load_torque / drivetrain.stall_torque)
        return speed, speed
    return scenario.initial.motor_speed, scenario.initial.drum_speed * drivetrain.ratio


@dataclass(frozen=True)
class ForceSchedule:
    """The engagement force table as arrays, with its kinks and steps as segment boundaries."""

    times: np.ndarray  # s, non-decreasing; a repeated time is a step
    forces: np.ndarray  # N

    @classmethod
    def from_scenario(cls, scenario: Scenario) -> "ForceSchedule":
        table = scenario.clutch.engagement_force
        return cls(np.asarray(table.times, dtype=float), np.asarray(table.forces, dtype=float))

    def __call__(self, t):
        """Force at time(s) t, right-continuous at steps (N)."""
        return force_at(self.times, self.forces, t, np)


def force_at(times, forces, t, xp):
    """Piecewise-linear engagement force, right-continuous at steps; ``xp`` is numpy or jax.numpy.

    Works for scalar or array ``t`` and for tables with repeated times (steps):
    the interval used is the last one that starts at or before ``t``.
    """
    t = xp.asarray(t)
    n = times.shape[0]
    if n == 1:
        return xp.broadcast_to(forces[0], t.shape) * xp.ones_like(t)
    # index of the last knot at or before t (right-continuous: a step at t is taken)
    k = xp.clip(xp.searchsorted(times, t, side="right") - 1, 0, n - 2)
    t0, t1 = times[k], times[k + 1]
    f0, f1 = forces[k], forces[k + 1]
    width = t1 - t0
    safe = xp.where(width > 0, width, 1.0)
    frac = xp.clip((t - t0) / safe, 0.0, 1.0)
    value = xp.where(width > 0, f0 + frac * (f1 - f0), f1)
    before = t < times[0]
    value = xp.where(before, forces[0], value)
    return xp.where(t >= times[-1], forces[-1], value)

"""The canonical hoist as two shafts meeting at the clutch: the oracles' own reduction.

Side a is the motor shaft; side b the clutch output (pinion) shaft.  Masses are
reduced by equal kinetic energy and forces by equal power (physics.md):

    J_a = J_motor + J_clutch,driving (+ a flywheel on the motor shaft)
    J_b = J_clutch,driven + J_pinion + (J_wheel + I_drum + M R^2 (+ a flywheel on the drum)) / tau^2
    T_L = M g R / tau

The simulator does not use these numbers: its elements declare inertias and
torques on their shafts, and the core reduces them.  The closed-form solution
(:mod:`hoistsim.references.exact`), the scipy reference, the statics and the reduced-model
table do, written here once and independently of the elements, so that the
oracles and the engine agree only if both are right.  They cover the canonical
scene: a linear motor, the cone clutch, gears, drum, a rigid load, a holding
brake, a flywheel.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._pytree import pytree_dataclass
from ..components import ConeClutch, Drum, GearPair, HangingLoad, LinearMotor
from ..errors import ScenarioError
from ..machine.core.element import MODE_NAMES as MODE_NAMES
from ..machine.core.element import OPEN as OPEN
from ..machine.core.element import SLIP_BACKWARD as SLIP_BACKWARD
from ..machine.core.element import SLIP_FORWARD as SLIP_FORWARD
from ..machine.core.element import SLIP_RESOLUTION as SLIP_RESOLUTION
from ..machine.core.element import STICK_TOLERANCE as STICK_TOLERANCE
from ..machine.core.element import STUCK as LOCKED
from ..machine.core.schedule import table_at
from ..scenario.loading import Scenario


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

    motor_flywheel: float = 0.0
    drum_flywheel: float = 0.0

    @classmethod
    def from_scenario(cls, scenario: Scenario) -> "Machine":
        m, c, g = scenario.motor, scenario.clutch, scenario.gears
        if m.characteristic != "linear":
            raise ScenarioError("motor", "the two-shaft reduction (statics, closed form) needs a linear motor "
                                "(stall_torque + no_load_speed)")
        flywheel = scenario.flywheel
        fly = flywheel.moment_of_inertia if flywheel is not None else 0.0
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
            motor_flywheel=fly if flywheel is not None and flywheel.shaft == "motor" else 0.0,
            drum_flywheel=fly if flywheel is not None and flywheel.shaft == "drum" else 0.0,
        )

    def reduced(self) -> "Drivetrain":
        tau = self.gears.ratio
        R = self.drum.rope_radius
        drum_side = self.gears.wheel_inertia + self.drum.inertia + self.drum_flywheel + self.load.mass * R**2
        return Drivetrain(
            motor_inertia=self.motor.inertia + self.driving_inertia + self.motor_flywheel,
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
    """The two-shaft reduced model (SI): plain floats (or numpy arrays)."""

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
    """Piecewise-linear engagement force, right-continuous at steps; ``xp`` is numpy or jax.numpy."""
    return table_at(times, forces, t, xp)

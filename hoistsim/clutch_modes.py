"""The clutch's modes: dynamics, guards and switching rules, as small pure functions.

Everything here works on JAX arrays (traced or batched).  The restart loop in
:mod:`hoistsim.hybrid` strings them together; keeping them apart makes each rule
easy to read and to test alone.

State vector y (SI):
    0 motor_speed     omega_a, rad/s
    1 output_speed    omega_b, rad/s (pinion shaft)
    2 load_position   m, up positive
    3 clutch_energy   J, dissipated by slip so far
    4 motor_work      J, done by the motor so far
"""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp

from .model import LOCKED, OPEN, SLIP_BACKWARD, SLIP_FORWARD, SLIP_RESOLUTION, STICK_TOLERANCE, Drivetrain

MOTOR_SPEED, OUTPUT_SPEED, LOAD_POSITION, CLUTCH_ENERGY, MOTOR_WORK = range(5)

STATE_SIZE = 5

# Event kinds, stored as codes in the compiled loop and as strings in the output.
# The last two are observations, not switches: instants where the slip speed
# peaks or the load turns round at its lowest point.  They become output rows,
# so peaks are exact rather than sampled, but not rows of the events table.
EVENT_KINDS = ("lock", "unlock", "reversal", "engage", "disengage", "brake_release", "slip_peak", "load_lowest")
SWITCH_KINDS = EVENT_KINDS[:6]
NO_EVENT = -1
LOCK, UNLOCK, REVERSAL, ENGAGE, DISENGAGE, BRAKE_RELEASE, SLIP_PEAK, LOAD_LOWEST = range(8)


class Segment(eqx.Module):
    """What holds between two scheduled boundaries: a linear force, a held or free drum."""

    start: object  # s
    end: object  # s
    force_start: object  # N, engagement force at ``start`` on this segment's line
    force_slope: object  # N/s
    drum_held: object  # bool, or None when no effect can hold the drum
    is_open: object  # bool: the force is zero on the whole segment

    def engagement_force(self, t):
        return self.force_start + self.force_slope * (t - self.start)


def slip_direction(mode):
    """+1 while the motor side runs faster, -1 while it runs slower, 0 when locked or open."""
    return jnp.where(mode == SLIP_FORWARD, 1.0, jnp.where(mode == SLIP_BACKWARD, -1.0, 0.0))


def locked_acceleration(drivetrain: Drivetrain, motor_torque, drum_held):
    """Common acceleration of both shafts when locked (rad/s^2); zero while the brake holds."""
    free = (motor_torque - drivetrain.load_torque) / (drivetrain.motor_inertia + drivetrain.output_inertia)
    return free if drum_held is None else jnp.where(drum_held, 0.0, free)


def locked_torque(drivetrain: Drivetrain, speed, drum_held):
    """Torque a locked clutch carries at shaft speed ``speed`` (N*m).

    Whatever of the motor torque does not accelerate the motor's own inertia:
    T_c = C - J_a alpha, i.e. (J_b C + J_a T_L)/(J_a + J_b) with a free drum and
    C itself while the brake holds the drum.
    """
    motor_torque = drivetrain.motor_torque(speed)
    return motor_torque - drivetrain.motor_inertia * locked_acceleration(drivetrain, motor_torque, drum_held)


def holding_capacity(drivetrain: Drivetrain, force):
    """The static capacity with the stick tolerance: what a locked clutch is allowed to carry."""
    return drivetrain.static_capacity(force) * (1.0 + STICK_TOLERANCE)


def static_check(drivetrain: Drivetrain, segment: Segment, t, speed):
    """Mode at zero slip: locked if the static capacity holds the locked torque, else slip its way."""
    torque = locked_torque(drivetrain, speed, segment.drum_held)
    capacity = holding_capacity(drivetrain, segment.engagement_force(t))
    return jnp.where(jnp.abs(torque) <= capacity, LOCKED,
                     jnp.where(torque > 0, SLIP_FORWARD, SLIP_BACKWARD))


class Rates(eqx.Module):
    """Torques and accelerations in a mode (arrays broadcast over rows)."""

    motor_torque: object
    clutch_torque: object
    motor_acceleration: object
    output_acceleration: object
    slip_power: object  # W dissipated in the clutch


def rates(drivetrain: Drivetrain, mode, force, motor_speed, output_speed, drum_held) -> Rates:
    """The equations of motion of physics.md for every mode at once, selected by ``mode``."""
    motor_torque = drivetrain.motor_torque(motor_speed)
    alpha_locked = locked_acceleration(drivetrain, motor_torque, drum_held)
    slip_torque = slip_direction(mode) * drivetrain.kinetic_torque(force)  # 0 when open
    output_free = (slip_torque - drivetrain.load_torque) / drivetrain.output_inertia
    output_slipping = output_free if drum_held is None else jnp.where(drum_held, 0.0, output_free)
    locked = mode == LOCKED
    return Rates(
        motor_torque=motor_torque,
        clutch_torque=jnp.where(locked, motor_torque - drivetrain.motor_inertia * alpha_locked, slip_torque),
        motor_acceleration=jnp.where(locked, alpha_locked, (motor_torque - slip_torque) / drivetrain.motor_inertia),
        output_acceleration=jnp.where(locked, alpha_locked, output_slipping),
        slip_power=slip_torque * (motor_speed - output_speed),
    )


def vector_field(t, y, args):
    drivetrain, segment, mode = args[:3]
    motor_speed, output_speed = y[MOTOR_SPEED], y[OUTPUT_SPEED]
    r = rates(drivetrain, mode, segment.engagement_force(t), motor_speed, output_speed, segment.drum_held)
    return jnp.stack([
        r.motor_acceleration,
        r.output_acceleration,
        drivetrain.load_speed(output_speed),
        r.slip_power,
        r.motor_torque * motor_speed,
    ])


# Guards: positive inside their mode, an event where they fall to zero.  Outside
# their mode they are a constant 1 and never fire.  ``args`` is (drivetrain,
# segment, mode, observing); ``observing`` switches the observation guards off
# once their budget is spent.  diffrax needs a strictly positive value before a
# non-positive one, so a guard that is exactly zero at a restart cannot fire.


def slip_guard(t, y, args, **kwargs):
    """Slip speed in the direction of slip, plus a negligible slip: reaches 0 when the two sides meet.

    After an unlock or a reversal the slip restarts at exactly zero.  Were the
    guard zero there too, an excursion that returns within the first step would
    go unseen (the crossing test needs a positive value first); offset by the
    slip resolution (~3e-14 rad/s) the guard starts positive.  It cannot fire at
    once: the stick tolerance makes the slip grow the right way from a restart.
    """
    drivetrain, segment, mode = args[:3]
    slip = y[MOTOR_SPEED] - y[OUTPUT_SPEED]
    s = slip_direction(mode)
    return jnp.where(s != 0.0, s * slip + SLIP_RESOLUTION * drivetrain.no_load_speed, 1.0)


def _capacity_margin(sign, t, y, args):
    drivetrain, segment, mode = args[:3]
    torque = locked_torque(drivetrain, y[MOTOR_SPEED], segment.drum_held)
    capacity = holding_capacity(drivetrain, segment.engagement_force(t))
    return jnp.where(mode == LOCKED, capacity - sign * torque, 1.0)


def forward_breakaway_guard(t, y, args, **kwargs):
    """Static capacity minus the locked torque: 0 when the motor side breaks away forwards."""
    return _capacity_margin(1.0, t, y, args)


def backward_breakaway_guard(t, y, args, **kwargs):
    """Static capacity plus the locked torque: 0 when the load side drags the clutch backwards."""
    return _capacity_margin(-1.0, t, y, args)


def slip_peak_guard(t, y, args, **kwargs):
    """Rate of change of |slip| while not locked: falls through zero where the slip speed peaks."""
    drivetrain, segment, mode = args[:3]
    r = rates(drivetrain, mode, segment.engagement_force(t), y[MOTOR_SPEED], y[OUTPUT_SPEED], segment.drum_held)
    slip = y[MOTOR_SPEED] - y[OUTPUT_SPEED]
    growth = jnp.sign(slip) * (r.motor_acceleration - r.output_acceleration)
    return jnp.where((mode != LOCKED) & args[3], growth, 1.0)


def load_turnaround_guard(t, y, args, **kwargs):
    """Minus the pinion speed: falls through zero where a load that ran back turns round (its lowest point).

    Written as a fall from strictly positive, so a drum starting from rest (or
    released by the brake) is not taken for a turnaround.
    """
    return jnp.where(args[3], -y[OUTPUT_SPEED], 1.0)


def slip_valley_guard(t, y, args, **kwargs):
    """Minus the rate of the slip in its direction: falls through zero where the slip stops shrinking.

    A safeguard, not an observation: with a loose tolerance one step can carry
    the slip below zero and back (in the slipping equations) so that neither end
    of the step shows the crossing.  The valley between is always detected; if
    the slip there is negative, the loop re-solves with shorter steps.
    """
    drivetrain, segment, mode, observing = args
    r = rates(drivetrain, mode, segment.engagement_force(t), y[MOTOR_SPEED], y[OUTPUT_SPEED], segment.drum_held)
    s = slip_direction(mode)
    return jnp.where((s != 0.0) & observing, -s * (r.motor_acceleration - r.output_acceleration), 1.0)


# Switching guards come first: when two guards cross in one step, diffrax locates
# the first in this order, and a switch must never be skipped for an observation.
GUARDS = (slip_guard, forward_breakaway_guard, backward_breakaway_guard, slip_peak_guard, load_turnaround_guard,
          slip_valley_guard)
SLIP_VALLEY = 5  # index of the valley guard


def transition_kind(previous, new):
    """Event kind recorded when a scheduled boundary changes the mode (NO_EVENT if none)."""
    slipping_before = (previous == SLIP_FORWARD) | (previous == SLIP_BACKWARD)
    kind = jnp.where(new == LOCKED, LOCK,
           jnp.where(new == OPEN, DISENGAGE,
           jnp.where(previous == LOCKED, UNLOCK,
           jnp.where(previous == OPEN, ENGAGE, REVERSAL))))
    changed = (previous != new) & ((previous == LOCKED) | (previous == OPEN) | slipping_before)
    return jnp.where(changed, kind, NO_EVENT)

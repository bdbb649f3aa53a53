"""Output time series computed from the integrated state, with their units.

Computed inside the compiled run (the same equations the integrator used), for
the output grid rows and for the event rows alike.
"""

from __future__ import annotations

import functools

import jax.numpy as jnp

from . import clutch_modes as cm
from .effects import RowContext
from .model import LOCKED, force_at


def drum_held(effects, t):
    """Whether any effect holds the drum at t; None when no effect of the scene can."""
    held = [h for h in (e.holds_drum(t) for e in effects) if h is not None]
    if not held:
        return None
    return functools.reduce(jnp.logical_or, held)

UNITS = {
    "time": "s",
    "motor_speed": "rad/s",
    "drum_speed": "rad/s",
    "slip_speed": "rad/s",
    "clutch_torque": "N*m",
    "clutch_locked": "1",
    "engagement_force": "N",
    "load_position": "m",
    "load_velocity": "m/s",
    "clutch_energy": "J",
    "clutch_capacity": "N*m",
    "clutch_mode": "1",
    "motor_torque": "N*m",
    "motor_work": "J",
}

DESCRIPTIONS = {
    "time": "time since the start",
    "motor_speed": "motor shaft speed (side a of the clutch)",
    "drum_speed": "drum speed, positive when the load goes up",
    "slip_speed": "motor speed minus clutch-output (pinion) speed",
    "clutch_torque": "torque through the clutch, positive when the motor drives the load",
    "clutch_locked": "1 while the clutch sticks, 0 while it slips or is open",
    "engagement_force": "axial force pressing the cone clutch",
    "load_position": "height of the load above its start",
    "load_velocity": "rope speed, positive up",
    "clutch_energy": "energy dissipated in the clutch so far",
    "clutch_capacity": "static torque capacity at the current engagement force",
    "clutch_mode": "0 locked, 1 slipping forwards, 2 slipping backwards, 3 open",
    "motor_torque": "motor torque from its characteristic",
    "motor_work": "work done by the motor so far",
}


def row_outputs(plan, t, y, mode) -> dict:
    """Every output column at rows (t, y, mode); ``y`` is (rows, STATE_SIZE)."""
    dt = plan.drivetrain
    motor_speed, output_speed = y[:, cm.MOTOR_SPEED], y[:, cm.OUTPUT_SPEED]
    force = force_at(plan.force_times, plan.force_values, t, jnp)
    held = drum_held(plan.effects, t)
    r = cm.rates(dt, mode, force, motor_speed, output_speed, held)
    out = {
        "motor_speed": motor_speed,
        "drum_speed": output_speed / dt.ratio,
        "slip_speed": motor_speed - output_speed,
        "clutch_torque": r.clutch_torque,
        "clutch_locked": (mode == LOCKED).astype(jnp.int8),
        "engagement_force": force,
        "load_position": y[:, cm.LOAD_POSITION],
        "load_velocity": dt.load_speed(output_speed),
        "clutch_energy": y[:, cm.CLUTCH_ENERGY],
        "clutch_capacity": dt.static_capacity(force),
        "clutch_mode": mode.astype(jnp.int8),
        "motor_torque": r.motor_torque,
        "motor_work": y[:, cm.MOTOR_WORK],
    }
    row = RowContext(
        time=t,
        motor_speed=motor_speed,
        output_speed=output_speed,
        motor_acceleration=r.motor_acceleration,
        output_acceleration=r.output_acceleration,
        motor_torque=r.motor_torque,
        clutch_torque=r.clutch_torque,
        engagement_force=force,
        drum_held=held,
    )
    for effect in plan.effects:
        out.update(effect.outputs(row, dt))
    return out


def units_of(effects) -> dict[str, str]:
    units = dict(UNITS)
    for effect in effects:
        units.update(effect.output_units)
    return units

"""The regularised friction model many users write instead of a hybrid one.

The clutch torque is made a smooth function of the slip speed,
T = f c F(t) tanh(slip / width): no modes, no events, one ODE.  It cannot
stick: a "locked" clutch creeps at the slip that makes tanh carry the torque,
and the kinetic coefficient alone sets what it can carry.  The smoothing width
therefore sets a floor under the error that no tolerance removes, and small
widths make the ODE stiff.  The work-precision study runs it to show both.
"""

from __future__ import annotations

import functools

import diffrax
import jax
import jax.numpy as jnp
import numpy as np

from . import clutch_modes as cm
from .hybrid import SOLVERS
from .model import force_at
from .series import drum_held
from .simulation import build_plan

MAX_STEPS = 200_000


def _vector_field(t, y, args):
    plan, width = args
    d = plan.drivetrain
    motor_speed, output_speed = y[cm.MOTOR_SPEED], y[cm.OUTPUT_SPEED]
    slip = motor_speed - output_speed
    torque = d.kinetic_torque(force_at(plan.force_times, plan.force_values, t, jnp)) * jnp.tanh(slip / width)
    motor_torque = d.motor_torque(motor_speed)
    output_acceleration = (torque - d.load_torque) / d.output_inertia
    held = drum_held(plan.effects, t)
    if held is not None:
        output_acceleration = jnp.where(held, 0.0, output_acceleration)
    return jnp.stack([
        (motor_torque - torque) / d.motor_inertia,
        output_acceleration,
        d.load_speed(output_speed),
        torque * slip,
        motor_torque * motor_speed,
    ])


def _solve(plan, width, solver):
    # The force table's kinks and the brake release are known jumps: the step
    # size controller steps onto them rather than through them.
    return diffrax.diffeqsolve(
        diffrax.ODETerm(_vector_field), solver, t0=0.0, t1=plan.duration, dt0=None, y0=plan.initial_state,
        args=(plan, width), saveat=diffrax.SaveAt(ts=plan.grid),
        stepsize_controller=diffrax.PIDController(rtol=plan.rtol, atol=plan.atol, jump_ts=jnp.sort(plan.boundaries)),
        max_steps=MAX_STEPS, throw=False, adjoint=diffrax.ForwardMode(),
    )


@functools.lru_cache(maxsize=None)
def compiled(solver_name: str):
    solver = SOLVERS[solver_name]()
    return jax.jit(lambda plan, width: _solve(plan, width, solver))


def simulate_regularised(scenario, width: float, solver: str = "tsit5"):
    """Run the scenario with tanh friction of ``width`` (rad/s); returns (time, states, stats).

    States are rows of (motor speed, pinion speed, load position, clutch energy,
    motor work) on the scenario's output grid; ``stats`` has ``steps`` and
    ``finished`` (False when the step limit was reached first).
    """
    plan, grid = build_plan(scenario)
    sol = jax.device_get(compiled(solver)(plan, jnp.asarray(width)))
    states = np.asarray(sol.ys)[: grid.size]
    return grid, states, {"steps": int(sol.stats["num_steps"]),
                          "finished": bool(sol.result == diffrax.RESULTS.successful)}

"""The regularised friction model many users write instead of a hybrid one.

Every coupling that can slip passes a smooth function of its slip speed,
T = T_k(t) tanh(slip / width): no modes, no events, one ODE, built from the
same elements as the hybrid run (only the couplings' sliding torque is
wrapped).  It cannot stick: a "locked" clutch creeps at the slip that makes
tanh carry the torque, and the kinetic coefficient alone sets what it can
carry.  The smoothing width therefore sets a floor under the error that no
tolerance removes, and small widths make the ODE stiff.  The work-precision
study runs it to show both.  Couplings that never slip (a holding brake) hold
while they are closed.
"""

from __future__ import annotations

import dataclasses
import functools

import diffrax
import jax
import jax.numpy as jnp
import numpy as np

from ..machine.assemble import build_plan
from ..machine.core.dynamics import vector_field
from ..machine.core.element import OPEN, SLIP_FORWARD, STUCK, AbstractCoupling
from ..machine.core.loop import SOLVERS, Args
from ..machine.core.schedule import Segment, table_at, tables_of

MAX_STEPS = 200_000


@functools.lru_cache(maxsize=None)
def _smooth(cls):
    """``cls`` whose sliding torque is T_k tanh(slip / width), signed: its mode stays slipping+."""

    class Smooth(cls):
        smoothing_width: object = 1.0

        def sliding_torque(self, x):
            return cls.sliding_torque(self, x) * jnp.tanh(x.relative_speed(self.section) / self.smoothing_width)

    Smooth.__name__ = f"Smooth{cls.__name__}"
    return Smooth


def _regularise(element, width):
    if not (isinstance(element, AbstractCoupling) and element.can_slip):
        return element
    smooth = _smooth(type(element))
    fields = {f.name: getattr(element, f.name) for f in dataclasses.fields(element)}
    return smooth(**fields, smoothing_width=width)


def _field(t, y, args):
    plan, width = args
    elements = tuple(_regularise(e, width) for e in plan.elements)
    tables = tables_of(elements)
    # A segment of zero length at t: the tables' values at t, and whether each coupling is closed at t.
    lines = {name: (table_at(times, values, t), jnp.zeros(())) for name, (times, values) in tables.items()}
    here = Segment(start=t, end=t, lines=lines)
    modes = jnp.stack([jnp.asarray(SLIP_FORWARD) if c.can_slip else jnp.where(c.is_open(here), OPEN, STUCK)
                       for c in elements if isinstance(c, AbstractCoupling)])
    args = Args(elements, here, modes, jnp.asarray(False), plan.speed_scale, None, {}, jnp.asarray(False), {}, {})
    return vector_field(t, y, args)


def _solve(plan, width, solver):
    # The tables' knots and the scheduled times are known jumps: the step size
    # controller steps onto them rather than through them.
    return diffrax.diffeqsolve(
        diffrax.ODETerm(_field), solver, t0=0.0, t1=plan.duration, dt0=None, y0=plan.initial_state,
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

    ``states`` maps each state's name (``motor.speed``, ``pinion.speed``,
    ``clutch_energy``, ...) to its values on the scenario's output grid;
    ``stats`` has ``steps`` and ``finished`` (False when the step limit was
    reached first).
    """
    plan, grid = build_plan(scenario)
    sol = jax.device_get(compiled(solver)(plan, jnp.asarray(width)))
    rows = np.asarray(sol.ys)[: grid.size]
    states = {name: rows[:, i] for i, name in enumerate(plan.layout.state_names)}
    return grid, states, {"steps": int(sol.stats["num_steps"]),
                          "finished": bool(sol.result == diffrax.RESULTS.successful)}

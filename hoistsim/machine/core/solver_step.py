"""One step of a diffrax solver as a pass takes it: an explicit Runge-Kutta step with its stages written out
from the tableau (any other solver, the implicit ones, through its own ``step``), and the vector field traced
once for all the stages that read it."""

from __future__ import annotations

import functools

import diffrax
import equinox as eqx
import jax
import jax.numpy as jnp

from . import private_api


@functools.lru_cache(maxsize=None)
def traced_once(field):
    """The vector field as a call of its own (a jitted function): a step reads it at each of its stages
    and a crossing's step again, and the program is traced and lowered with one copy of it instead of one
    a stage.  (XLA inlines the calls: the compiled program computes the same.)"""
    return jax.jit(field)


class Stepper:
    """One step of an explicit Runge-Kutta solver, its stages written out from the tableau; any other
    diffrax solver (the implicit ones) through its own ``step``."""

    def __init__(self, solver, args, field):
        self.solver, self.args, self.vector_field = solver, args, traced_once(field)
        self.term = diffrax.ODETerm(field)
        tableau = getattr(solver, "tableau", None)
        self.explicit = isinstance(solver, diffrax.AbstractERK) and tableau is not None
        if self.explicit:
            self.a = [[float(v) for v in row] for row in tableau.a_lower]
            self.c = [float(v) for v in tableau.c]
            self.b = [float(v) for v in tableau.b_sol]
            self.e = [float(v) for v in tableau.b_error]
            self.fsal, self.ssal = bool(tableau.fsal), bool(tableau.ssal)

    def field(self, t, y):
        return self.vector_field(t, y, self.args)

    def init(self, t0, t1, y0):
        """The state a step carries: the rate at its start (explicit), or the solver's own state."""
        if self.explicit:
            return self.field(t0, y0)
        return self.solver.init(self.term, t0, t1, y0, self.args)

    def step(self, t0, t1, y0, state):
        """(y1, error estimate, dense info, state after it, whether it could be taken)."""
        if not self.explicit:
            y1, error, dense, state, result = self.solver.step(self.term, t0, t1, y0, self.args, state, False)
            return y1, error, dense, state, result == diffrax.RESULTS.successful
        h = t1 - t0
        rates = [state if self.fsal else self.field(t0, y0)]

        def combined(weights):
            return sum((w * k for w, k in zip(weights, rates) if w != 0.0), jnp.zeros_like(y0))

        y1 = None
        for row, c in zip(self.a, self.c):
            last = len(rates) == len(self.a)
            if last and self.ssal:
                y1 = y0 + h * combined(row)
                stage = y1
            else:
                stage = y0 + h * combined(row)
            rates.append(self.field(t0 + c * h, stage))
        if y1 is None:
            y1 = y0 + h * combined(self.b)
        error = h * combined(self.e)
        dense = dict(y0=y0, y1=y1, k=h * jnp.stack(rates))
        return y1, error, dense, rates[-1] if self.fsal else state, jnp.ones((), bool)

    def interpolant(self, t0, t1, dense):
        return self.solver.interpolation_cls(t0=t0, t1=t1, **dense)


def with_step_tolerances(solver, controller):
    """An implicit solver whose nonlinear solve takes the step controller's tolerances where it leaves them
    to it (diffrax's default; ``diffeqsolve`` does the same)."""
    if not isinstance(solver, diffrax.AbstractImplicitSolver):
        return solver
    names = [name for name in ("rtol", "atol", "norm")
             if getattr(solver.root_finder, name) is private_api.use_stepsize_tol]
    return eqx.tree_at(lambda s: tuple(getattr(s.root_finder, name) for name in names), solver,
                       tuple(getattr(controller, name) for name in names))

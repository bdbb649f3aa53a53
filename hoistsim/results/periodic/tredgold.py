"""The turning-moment diagram at constant speed, and Tredgold's degree of irregularity.

Tredgold's method takes the machine rigid (every coupling between two shafts
stuck), its speed constant at the mean speed w_m, and so the inertia forces of
reciprocating parts as torques at that speed (the seed's second hypothesis:
the slider-crank's -1/2 I'(theta) w_m^2); its inertia I is then the constant
part, reduced to the motor shaft.  The driving torque M'_m (the motor's
elements) and the resisting torque M'_r (all the others, sign turned) are
evaluated over one period; the energy E(theta) = integral of (M'_m - M'_r)
has its extremes where the curves cross, and

    Delta E_max = max E - min E,    delta = Delta E_max / (I w_m^2).

The integral is exact to round-off: Gauss-Legendre on intervals that end at
every knot of a table (where the torque has a kink) and at every crossing
(found by root-finding), so each piece is smooth.
"""

from __future__ import annotations

from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from ... import _jax  # noqa: F401  (float64 before any array)
from ...machine.core.bodies import Bodies
from ...machine.core.dynamics import Instant
from ...machine.core.element import OPEN, STUCK
from ...machine.core.layout import Layout, angle_state
from ...machine.core.schedule import table_at, tables_of

# Intervals per period before knots and crossings are added; Gauss-Legendre nodes per interval.
INTERVALS = 2048
HALVINGS = 64  # a root's bracket halved at most this many times (from a grid interval to 2e-15: some 40)
NODES, WEIGHTS = np.polynomial.legendre.leggauss(6)


@dataclass
class Diagram:
    """One period of the turning-moment diagram at the motor shaft, and Tredgold's answer."""

    angle: np.ndarray  # rad from the period's start
    driving: np.ndarray  # N*m, M'_m at the motor shaft
    resisting: np.ndarray  # N*m, M'_r at the motor shaft (positive when it resists)
    energy: np.ndarray  # J, integral of (M'_m - M'_r) from the period's start
    mean_speed: float  # rad/s, the speed the diagram is taken at
    inertia: float  # kg*m^2, the machine's constant inertia at the motor shaft
    energy_fluctuation: float  # J, Delta E_max
    min_speed_angle: float  # theta_1 (rad from the start): where E is least
    max_speed_angle: float  # theta_2: where E is greatest
    work_residual: float  # J, E at the period's end (zero when the mean torques balance)

    @property
    def mean_energy(self) -> float:
        """The mean over angle of E (J): where E stands when the kinetic energy is at its mean."""
        pieces = 0.5 * (self.energy[1:] + self.energy[:-1]) * np.diff(self.angle)
        return float(np.sum(pieces) / (self.angle[-1] - self.angle[0]))

    @property
    def irregularity(self) -> float:
        return self.energy_fluctuation / (self.inertia * self.mean_speed**2)

    def required_inertia(self, irregularity: float) -> float:
        """The whole inertia at the motor shaft that keeps delta at ``irregularity``, by Tredgold."""
        return self.energy_fluctuation / (irregularity * self.mean_speed**2)


def _rigid_ratios(layout: Layout) -> list:
    """Each body's speed per unit motor speed with every coupling between two shafts stuck."""
    rows = [row for row, coupling in zip(Bodies(layout).rows, layout.coupling_elements)
            if coupling.joins()[1] is not None]
    motor, _ = layout.shaft("motor")
    n = len(layout.bodies)
    if not rows:
        return [1.0 if i == motor else 0.0 for i in range(n)]
    g = jnp.stack([jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in row]) for row in rows])
    others = [i for i in range(n) if i != motor]
    # G v = 0 with v_motor = 1: G[:, others] v_others = -G[:, motor]
    v = jnp.linalg.lstsq(g[:, others], -g[:, motor])[0]
    out = [jnp.ones(())] * n
    for k, i in enumerate(others):
        out[i] = v[k]
    return out


def _shaft_ratio(layout: Layout, ratios, shaft):
    body, ratio = layout.shaft(shaft)
    return ratio * ratios[body]


def _is_driving(element) -> bool:
    return element.section == "motor" or element.section.startswith("motor.")


def _torques(elements, start_state, time, speed, angle):
    """(M'_m, M'_r, knot coordinates) at the motor shaft at a motor angle from the period's start."""
    layout = Layout(elements)
    ratios = _rigid_ratios(layout)
    y = start_state
    for i in range(len(layout.bodies)):
        y = y.at[i].set(speed * ratios[i])
    for shaft in layout.angle_shafts:
        index = layout.state_index(angle_state(shaft))
        y = y.at[index].set(start_state[index] + angle * _shaft_ratio(layout, ratios, shaft))
    modes = jnp.asarray([OPEN if c.joins()[1] is None else STUCK for c in layout.coupling_elements], dtype=int)
    tables = tables_of(elements)
    x = Instant(layout, time, y, modes, lambda name, t: table_at(*tables[name], t))
    driving, resisting = 0.0, 0.0
    for element in elements:
        for shaft, torque in element.torques(x):
            at_motor = torque * _shaft_ratio(layout, ratios, shaft)  # equal power
            if _is_driving(element):
                driving = driving + at_motor
            else:
                resisting = resisting - at_motor
    knots = [value for e in elements if not e.cycles for value in e.kinks(x).values()]
    return jnp.asarray(driving), jnp.asarray(resisting), jnp.stack(knots) if knots else jnp.zeros((0,))


@jax.jit
def _torques_at(elements, start_state, time, speed, angles):
    return jax.vmap(lambda a: _torques(elements, start_state, time, speed, a))(angles)


@jax.jit
def _inertia_at_motor(elements):
    layout = Layout(elements)
    ratios = _rigid_ratios(layout)
    total = 0.0
    for element in elements:
        for shaft, value in element.inertias():
            total = total + value * _shaft_ratio(layout, ratios, shaft) ** 2
    return jnp.asarray(total)


def constant_inertia(elements) -> float:
    """The machine's constant inertia at the motor shaft, every coupling between two shafts stuck."""
    return float(_inertia_at_motor(elements))


def _roots(f, a, b) -> np.ndarray:
    """The root of ``f`` in each bracket [a_i, b_i], all at once: ``f`` takes an array of angles, one a bracket,
    and gives the values there.  Each bracket is halved until it is as narrow as a root's resolution (2e-15 of
    1 + |a|, scipy's ``brentq`` at xtol = rtol = 1e-15); its end nearer zero is the root.  One evaluation a round
    serves every bracket (a period's 144 knots: some 50 calls of the compiled torques, against a thousand, one
    root at a time).  A bracket whose ends are on one side by round-off has its root at the nearer end."""
    a, b = np.array(a, dtype=float), np.array(b, dtype=float)
    if a.size == 0:
        return a
    fa, fb = f(a), f(b)
    apart = fa * fb <= 0.0
    for _ in range(HALVINGS):
        if not np.any(apart & (b - a > 2e-15 * (1.0 + np.abs(a)))):
            break
        middle = 0.5 * (a + b)
        fm = f(middle)
        lower = apart & (fa * fm <= 0.0)  # the root in [a, middle]
        upper = apart & ~lower
        b, fb = np.where(lower, middle, b), np.where(lower, fm, fb)
        a, fa = np.where(upper, middle, a), np.where(upper, fm, fa)
    return np.where(np.abs(fa) <= np.abs(fb), a, b)


def diagram(elements, start_state, time: float, speed: float, period: float) -> Diagram:
    """The turning-moment diagram over one period from a state (angles where the period starts)."""
    start_state = np.asarray(start_state, dtype=np.float64)

    def at(angles):
        # padded to a power of two: a handful of compiled shapes serve every call
        angles = np.atleast_1d(np.asarray(angles, float))
        size = 1 << int(np.ceil(np.log2(max(angles.size, 1))))
        padded = np.concatenate([angles, np.full(size - angles.size, angles[-1])])
        return [np.asarray(v)[: angles.size] for v in _torques_at(elements, start_state, time, speed, padded)]

    def net(angles):
        m, r, _ = at(angles)
        return m - r

    grid = np.linspace(0.0, period, INTERVALS + 1)
    _, _, knots = at(grid)
    points = [grid]
    # table knots: where a knot coordinate passes a whole number, it is linear in the angle either side
    which, starts, targets = [], [], []
    for k in range(knots.shape[1] if knots.ndim == 2 else 0):
        u = knots[:, k]
        passed = np.flatnonzero(np.floor(u[1:] + 1e-12) != np.floor(u[:-1] + 1e-12))
        which += [k] * passed.size
        starts += list(passed)
        targets += list(np.floor(u[passed + 1] + 1e-12))
    which, starts, targets = np.array(which, dtype=int), np.array(starts, dtype=int), np.array(targets)
    points.append(_roots(lambda a: at(a)[2][np.arange(a.size), which] - targets, grid[starts], grid[starts + 1]))
    edges = np.unique(np.concatenate([np.atleast_1d(np.asarray(p, float)) for p in points]))
    # crossings of the two curves: the extremes of E
    sign = np.sign(net(edges))
    apart = np.flatnonzero(sign[:-1] * sign[1:] < 0)
    edges = np.unique(np.concatenate([edges, _roots(net, edges[apart], edges[apart + 1])]))
    left, width = edges[:-1], np.diff(edges)
    nodes = left[:, None] + 0.5 * width[:, None] * (NODES[None, :] + 1.0)
    pieces = 0.5 * width * (net(nodes.ravel()).reshape(nodes.shape) @ WEIGHTS)
    energy = np.concatenate([[0.0], np.cumsum(pieces)])
    driving, resisting, _ = at(edges)
    low, high = int(np.argmin(energy)), int(np.argmax(energy))
    return Diagram(angle=edges, driving=driving, resisting=resisting, energy=energy, mean_speed=speed,
                   inertia=constant_inertia(elements), energy_fluctuation=float(energy[high] - energy[low]),
                   min_speed_angle=float(edges[low]), max_speed_angle=float(edges[high]),
                   work_residual=float(energy[-1]))


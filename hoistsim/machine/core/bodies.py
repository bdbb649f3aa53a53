"""The bodies and their constrained solve: inertias, the couplings' rows, the response to torques.

The bodies' equations M a = tau - G^T T are solved for whichever couplings are
stuck: their torques T_s come from the small system (G_s M^-1 G_s^T) T_s =
G_s M^-1 f, where f is the bodies' torques less what the slipping couplings
pass, and the same system on speeds keeps momentum when couplings lock.  M is
diagonal (one inertia per body, an array) and G a small matrix (a row per
coupling over the bodies).  The system is solved on whole arrays: the rows and
columns of couplings not stuck masked to the identity, then Gauss-Jordan
elimination, each pivot one rank-1 update of the matrix and of every right-hand
side at once.
The pivots are unrolled at trace time, so the program grows with the couplings
as their count, not as the system's entries: one compiled program for every
combination of stuck couplings, vmappable, with no linear-algebra call (whose
pivoting would not keep the rule below).  Couplings that hold the same motion
twice (two holds on one shaft) share it by order: the first takes the torque,
the other carries none.

While the modes hold (a pass of the loop) the solution is a fixed linear map
from the bodies' torques tau and the slipping couplings' torques sigma to the
accelerations and the couplings' torques: :class:`Response`, four small
matrices worked out once per pass, so that each step of the integrator pays a
few matrix-vector products.  Those and the solve's own are written as products
summed (:func:`product`), which the compiler fuses with their neighbours: a dot
a few entries long would be a kernel of its own, slower to compile than to run.
"""

from __future__ import annotations

import functools
from functools import cached_property

import jax
import jax.numpy as jnp
import numpy as np

from ..._pytree import pytree_dataclass
from .element import STUCK
from .layout import Layout, angle_state


def _summed(shape, places, values):
    """An array of ``shape``: zero, but for each of ``values`` added at its place in ``places`` (index tuples).

    Numbers alone make a constant (a NumPy array, worked out as it is traced); traced values (a swept ratio, an
    inertia that varies with an angle) each place's sum, stacked: elementwise operations that fuse with what
    makes and uses them (a scatter is an operation of its own, and one a stage where an inertia varies)."""
    if all(isinstance(v, (int, float)) for v in values):
        out = np.zeros(shape)
        for place, value in zip(places, values):
            out[place] += value
        return out
    sums = {}
    for place, value in zip(places, values):  # in order, from zero: the scatter's own sums
        key = tuple(np.atleast_1d(place))
        sums[key] = sums.get(key, 0.0) + value
    return jnp.stack([jnp.asarray(sums.get(place, 0.0), dtype=jnp.float64)
                      for place in np.ndindex(*shape)]).reshape(shape)


# A product over at most this many columns, an elimination of at most this many pivots and an alignment of at
# most this many rounds are written out; larger ones are summed over an axis or looped, one column's, pivot's
# or round's operations in the program whatever their number.
UNROLLED = 4


def product(a, b):
    """The matrix product a b (b a vector or a matrix).  A few bodies and couplings make dots too small for a
    matrix kernel of their own; a sum over an axis (a reduction) is where XLA ends a fusion, and in a step's
    vector field it split each stage into fusions of their own (a third more operations a step on a two-body
    machine).  So a narrow product is a's columns times b's entries (rows), added: elementwise, fused with what
    makes and uses it.  A wide one is summed over its axis: written out, its operations would grow with the
    columns in every place a vector field is read, and XLA's compile with them."""
    if a.shape[1] > UNROLLED:
        return jnp.sum(a * b[None, :] if b.ndim == 1 else a[:, :, None] * b[None, :, :], axis=1)
    if a.shape[1] == 0:
        return jnp.zeros((a.shape[0],) + b.shape[1:], jnp.result_type(a, b))
    column = (lambda j: a[:, j] * b[j]) if b.ndim == 1 else (lambda j: a[:, j, None] * b[j][None, :])
    return functools.reduce(jnp.add, (column(j) for j in range(a.shape[1])))


def _vector(values):
    """A vector of ``values``: a constant if they are numbers, else one stack of them."""
    if all(isinstance(v, (int, float)) for v in values):
        return np.asarray(values, dtype=float)
    return jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in values])


# A stuck coupling whose pivot, once the couplings before it are eliminated, is below this fraction of
# its own diagonal holds a motion those couplings already hold (exactly zero but for round-off, some 1e-16).
# Not larger: a hold on a light shaft that a three-shaft linkage ties to heavy ones (1e-9 kg*m^2 against 1 and
# 10) has a pivot 7e-10 of its diagonal, and taken for a motion held twice it would hold nothing.
REDUNDANT_PIVOT = 1e-12


def solve_stuck(matrix, rhs, stuck, order=None):
    """Solve the stuck rows of a small symmetric positive-semidefinite system for several right-hand sides.

    ``matrix``: n x n; ``rhs``: n x m, a right-hand side a column; ``stuck``: n
    booleans.  Rows and columns of couplings that are not stuck become identity
    rows with a zero right-hand side, so their unknowns are zero.  Gauss-Jordan
    elimination without pivoting, in ``order`` (default: as given), is exact
    enough here: the masked matrix is positive definite unless stuck couplings
    hold the same motion twice (two holds on one shaft).  Then the torque is
    statically indeterminate: a coupling that the ones before it in ``order``
    already hold is given none (its pivot vanishes but for round-off), and they
    carry it all.  The matrix and its right-hand sides are one array, and each
    pivot one step on it: its row divided by the pivot (or made an identity row
    with a zero right-hand side, where it holds nothing new), then taken from
    every other row; what is left on the right is the solution.
    """
    n = matrix.shape[0]
    order = range(n) if order is None else order
    stuck = jnp.asarray(stuck, dtype=bool).reshape(n)
    identity = np.eye(n)
    diagonal = jnp.where(stuck, jnp.diagonal(matrix), 1.0)
    m = jnp.concatenate([jnp.where(stuck[:, None] & stuck[None, :], matrix, identity),
                         jnp.where(stuck[:, None], rhs, 0.0)], axis=1)
    unit = np.hstack([identity, np.zeros(rhs.shape)])  # an identity row, its right-hand side zero

    def eliminated(m, k):  # the pivot on row k taken: row k scaled to it, its column cleared from the others
        pivot = m[k, k]
        row = jnp.where(pivot <= REDUNDANT_PIVOT * diagonal[k], jnp.asarray(unit)[k], m[k] / pivot)
        return jnp.where((np.arange(n) == k)[:, None], row, m - m[:, k, None] * row)

    if n <= UNROLLED:  # a few pivots, written out
        for k in order:
            m = eliminated(m, k)
    else:  # one pivot's operations, looped: a program that does not grow with the couplings
        pivots = jnp.asarray(list(order))
        m = jax.lax.fori_loop(0, n, lambda i, m: eliminated(m, pivots[i]), m)
    return m[:, n:]


class Bodies:
    """The bodies' inertias and the couplings' rows of G (their shafts' speed ratios), by equal energy.

    ``y``: the state, needed only where an inertia varies with an angle.
    """

    def __init__(self, layout: Layout, y=None):
        self.layout = layout
        self.y = y
        count = len(layout.bodies)
        # (body a, ratio a, body b or None, ratio b) of each coupling; None for one that ties more shafts
        self.ends = []
        # each coupling's entries of G where it touches a body, by body: a relative speed sums these terms
        # alone, so that the relative speed of shafts locked at ratio one is their difference (exactly zero),
        # whatever the compiler fuses with it
        self.terms = []
        for coupling in layout.coupling_elements:
            row = {}
            for shaft, weight in coupling.weights():
                body, ratio = layout.shaft(shaft, coupling)
                row[body] = row[body] + weight * ratio if body in row else weight * ratio
            self.terms.append(sorted(row.items()))
            sides = coupling.joins()
            if len(sides) == 2:
                a, b = sides
                body_a, ratio_a = layout.shaft(a, coupling)
                body_b, ratio_b = layout.shaft(b, coupling) if b is not None else (None, 0.0)
                self.ends.append((body_a, ratio_a, body_b, ratio_b))
            else:
                self.ends.append(None)
        self.rows = _summed((len(self.ends), count), [(k, j) for k, row in enumerate(self.terms) for j, _ in row],
                            [g for row in self.terms for _, g in row])  # G, couplings x bodies
        self.driven = [k for k, c in enumerate(layout.coupling_elements) if c.drives]  # the drives, by coupling

    @cached_property
    def inertia(self):
        """Each body's inertia (an array): every element's inertia on a shaft of it, times the shaft's ratio
        squared."""
        places, values = [], []
        for element in self.layout.elements:
            for shaft, value in element.inertias():
                body, ratio = self.layout.shaft(shaft, element)
                places.append((body,))
                values.append(value * ratio**2)
        for element, shaft, value, _ in self.varying():
            body, ratio = self.layout.shaft(shaft, element)
            places.append((body,))
            values.append(value * ratio**2)
        return _summed((len(self.layout.bodies),), places, values)

    def varying(self) -> list:
        """(element, shaft, I, dI/dangle) of every inertia that varies with an angle, at the state y
        (none without a state: the bodies' constant inertia alone)."""
        if not self.layout.inertia_varies or self.y is None:
            return []

        def angle(shaft):
            return self.y[self.layout.state_index(angle_state(shaft))]

        return [(e, shaft, value, slope) for e in self.layout.elements if e.inertia_varies
                for shaft, value, slope in e.varying_inertias(angle)]

    @property
    def order(self) -> list:
        """The couplings in the order they take a torque that two of them could hold: those that hold first, then
        the rest, those that yield last."""
        couplings = self.layout.coupling_elements
        return sorted(range(len(couplings)), key=lambda k: (not couplings[k].holds_first, couplings[k].yields))

    def relative(self, k, values):
        """Coupling k's relative speed (or acceleration) for the bodies' speeds (or accelerations)."""
        return sum((g * values[j] for j, g in self.terms[k]), 0.0)

    def schur(self):
        """G M^-1 G^T, couplings x couplings."""
        g = self.rows
        return jnp.sum(g[:, None, :] * g[None, :, :] / self.inertia, axis=-1)

    def push(self, passed):
        """-G^T T: what the couplings' torques T take from side a and give to side b, per body (T a vector,
        or a matrix of them a column each)."""
        return -product(self.rows.T, passed)

    def align(self, values, stuck, held=None):
        """Make the values of bodies joined by stuck couplings agree to the last bit.

        ``values``: one per body, a vector or a matrix (a row per body, every column aligned alike).
        ``held``: the relative value each stuck coupling to the ground holds its body at, a row per coupling
        like ``values``' (a drive's speed or acceleration); None: none but zero, the ground at rest.
        Solved in floating point the constraints hold to round-off only; left so,
        two locked shafts would drift apart by ulps a step, and a held shaft would
        creep.  Bodies joined by stuck couplings between two shafts are groups,
        found on the whole arrays: each body takes the lowest body of its group as
        its root (the ground, below them all, where a stuck ground coupling holds
        one of them), carried a coupling further each round, with the speed
        ratios met on the way; each body's value is then its root's times that
        ratio (at the ground, what its hold holds), picked by a mask, not computed, so a shaft
        locked at ratio one has its root's value to the last bit.  A stuck
        coupling that ties three shafts, after them, gives one of its bodies not
        yet settled the value its relation leaves it: the one its row weighs most
        against its inertia (g^2 / m), whose value the solve finds as a small
        difference of large terms (a light shaft's, drifting off the relation and
        its torque doing work on round-off, else); its bodies are settled then.
        """
        count, nc = len(self.layout.bodies), len(self.ends)
        stuck = jnp.asarray(stuck, dtype=bool).reshape(nc)
        vector = values.ndim == 1
        values = values.reshape(count, -1)
        bodies = np.arange(count)
        root = jnp.asarray(bodies)
        ratio = jnp.ones(count)  # each body's value over its root's
        # which body each ground coupling holds (couplings x bodies), and which it holds now
        holds = np.asarray([[end is not None and end[2] is None and end[0] == j for j in bodies] for end in self.ends],
                           dtype=bool).reshape(nc, count)
        settled = jnp.any(holds & stuck[:, None], axis=0)
        # a held body's root is the ground (-1), or with drives the hold that holds it (-1 - k: coupling k)
        root = jnp.where(settled, -1 if held is None else -1 - jnp.argmax(holds & stuck[:, None], axis=0), root)
        pairs = [(k, *end) for k, end in enumerate(self.ends)
                 if end is not None and end[2] is not None and end[0] != end[2]]
        if pairs:
            # each pair twice, as an edge into either end: its coupling, the body it sets, the body it reads
            # from, and the ratio of their values
            edges = ([(k, a, b, (rb, ra)) for k, a, ra, b, rb in pairs]
                     + [(k, b, a, (ra, rb)) for k, a, ra, b, rb in pairs])
            of = np.asarray([[k == i for i in range(nc)] for k, *_ in edges])  # edges x couplings
            into = np.asarray([[a == j for _, a, _, _ in edges] for j in bodies])  # bodies x edges
            source = np.asarray([[b == j for j in bodies] for _, _, b, _ in edges])  # edges x bodies
            over = _vector([top / bottom for *_, (top, bottom) in edges])
            into = into & jnp.any(of & stuck, axis=1)  # the stuck edges into each body
            settled = settled | jnp.any(into, axis=1)
            def carried_on(_, found):  # a round carries the roots one coupling further
                root, ratio = found
                offered = jnp.where(into, jnp.sum(jnp.where(source, root, 0), axis=1), count)
                lowest = jnp.min(offered, axis=1)
                chosen = jnp.argmin(offered, axis=1)[:, None] == np.arange(len(edges))  # the first of them
                carried = jnp.sum(jnp.where(source, ratio, 0.0), axis=1) * over
                lower = lowest < root
                return (jnp.where(lower, lowest, root),
                        jnp.where(lower, jnp.sum(jnp.where(chosen, carried, 0.0), axis=1), ratio))

            rounds = min(count - 1, len(pairs))
            # a few rounds written out; more, one round's operations looped (the program does not grow with them)
            if rounds <= UNROLLED:
                for i in range(rounds):
                    root, ratio = carried_on(i, (root, ratio))
            else:
                root, ratio = jax.lax.fori_loop(0, rounds, carried_on, (root, ratio))
        if pairs or holds.any():
            # each body's root's value by a mask: one term of the sum is not zero (none at the ground)
            picked = (root[:, None] == bodies)[:, :, None]
            rooted = jnp.sum(jnp.where(picked, values, 0.0), axis=1)
            if held is not None:  # the value a hold holds its body at: its relative value over its speed ratio
                by_hold = (root[:, None] == -1 - np.arange(nc))[:, :, None]
                ratio_of = _vector([end[1] if end is not None and end[2] is None else 1.0 for end in self.ends])
                rooted = rooted + jnp.sum(jnp.where(by_hold, (held.reshape(nc, -1) / ratio_of[:, None])[None], 0.0),
                                          axis=1)
            values = rooted * ratio[:, None]
        for k, end in enumerate(self.ends):
            if end is not None:
                continue
            row, touched = self.rows[k], np.isin(bodies, [j for j, _ in self.terms[k]])
            # the unsettled body of the largest g^2 / m, the first of equals
            score = jnp.where(touched & ~settled, row**2 / self.inertia, -1.0)
            chosen = (bodies == jnp.argmax(score)) & (jnp.max(score) >= 0.0) & stuck[k]
            rest = jnp.sum(jnp.where(chosen[:, None], 0.0, row[:, None] * values), axis=0)  # the relation's others
            weight = jnp.where(jnp.any(chosen), jnp.sum(jnp.where(chosen, row, 0.0)), 1.0)  # none chosen: unused
            given = -rest / weight
            values = jnp.where(chosen[:, None], given, values)
            settled = settled | (touched & stuck[k])
        return values[:, 0] if vector else values


@pytree_dataclass
class Response:
    """The bodies' response while the modes hold: a = P tau + Q sigma + D h, T = R tau + U sigma + E h.

    tau: torques on the bodies; sigma: each coupling's sliding torque with the
    sign of its slip (zero unless slipping); h: the relative acceleration each
    drive holds (none without drives); a: accelerations; T: the torque
    each coupling passes.  Small arrays, so that a step evaluates them as a
    few matrix-vector products.  The rows of P and Q of bodies joined by stuck
    couplings at ratio one are equal to the last bit (zero for a body held to
    the ground), so their accelerations agree to the last bit.
    """

    accel_from_torque: jax.Array  # P, bodies x bodies
    accel_from_sliding: jax.Array  # Q, bodies x couplings
    torque_from_torque: jax.Array  # R, couplings x bodies
    torque_from_sliding: jax.Array  # U, couplings x couplings
    accel_from_motion: jax.Array  # D, bodies x drives
    torque_from_motion: jax.Array  # E, couplings x drives


def solve_response(layout: Layout, stuck, y=None) -> Response:
    """The linear map of :class:`Response` for a set of stuck couplings: one masked solve whose right-hand
    sides are a unit torque on each body, a unit sliding torque of each coupling and a unit relative
    acceleration held by each drive, side by side.

    ``y``: the state, where an inertia varies with an angle.
    """
    bodies = Bodies(layout, y)
    nb, nc = len(layout.bodies), len(bodies.ends)
    stuck = jnp.asarray(stuck, dtype=bool).reshape(nc)
    slips = np.diag([1.0 if e.can_slip else 0.0 for e in layout.coupling_elements])  # others' sigma is zero
    nd = len(bodies.driven)
    # the inputs a column each: a unit torque on each body, a unit sliding torque of each coupling, then a unit
    # relative acceleration held by each drive
    tau = np.hstack([np.eye(nb), np.zeros((nb, nc + nd))])
    sigma = np.hstack([np.zeros((nc, nb)), slips, np.zeros((nc, nd))])
    motion = np.hstack([np.zeros((nc, nb + nc)), np.eye(nc)[:, bodies.driven]])
    # the stuck couplings' system, its right-hand side the relative accelerations the free bodies would take
    # less those the drives hold
    free = tau + bodies.push(sigma)
    wanted = product(bodies.rows, free / bodies.inertia[:, None])
    held = solve_stuck(bodies.schur(), wanted - motion if nd else wanted, stuck, bodies.order)
    passed = jnp.where(stuck[:, None], held, sigma)
    accel = bodies.align((tau + bodies.push(passed)) / bodies.inertia[:, None], stuck, motion if nd else None)
    return Response(accel_from_torque=accel[:, :nb], accel_from_sliding=accel[:, nb:nb + nc],
                    torque_from_torque=passed[:, :nb], torque_from_sliding=passed[:, nb:nb + nc],
                    accel_from_motion=accel[:, nb + nc:], torque_from_motion=passed[:, nb + nc:])


def response(layout: Layout, modes, y=None) -> Response:
    """The bodies' response for these modes (``y``: the state, where an inertia varies with an angle)."""
    return solve_response(layout, jnp.asarray(modes)[: len(layout.couplings)] == STUCK, y)


def keep_momentum(layout: Layout, y, stuck, held=None):
    """Speeds after the ``stuck`` couplings lock: the nearest in kinetic energy, momentum kept.

    v+ = v - M^-1 G_s^T mu with (G_s M^-1 G_s^T) mu = G_s v - h: the impulses of the
    locking couplings, and nothing else, change the speeds.  ``held`` (h): the relative speed each coupling
    holds, a drive's its own (:meth:`Instant.held_speeds`), every other's zero; None: no drives.  A drive's
    impulse does the work -mu (r- + r+) / 2 (r its relative speed before and after: the kinetic energy it
    gives), added to its work state, so that a drive's speed that jumps (a step, an angle's kink) keeps the
    ledger whole.
    """
    bodies = Bodies(layout, y)
    if not bodies.ends:
        return y
    speeds = y[: len(layout.bodies)]
    relative = product(bodies.rows, speeds)
    impulse = solve_stuck(bodies.schur(), (relative if held is None else relative - held)[:, None], stuck,
                          bodies.order)[:, 0]
    speeds = bodies.align(speeds + bodies.push(impulse) / bodies.inertia, stuck, held)
    y = y.at[: len(layout.bodies)].set(speeds)
    for k in bodies.driven:
        work = -impulse[k] * 0.5 * (relative[k] + held[k])
        y = y.at[layout.state_index(layout.coupling_elements[k].work_state)].add(jnp.where(stuck[k], work, 0.0))
    return y

"""The bodies and their constrained solve: inertias, the couplings' rows, the response to torques.

The bodies' equations M a = tau - G^T T are solved for whichever couplings are
stuck: their torques T_s come from the small system (G_s M^-1 G_s^T) T_s =
G_s M^-1 f, where f is the bodies' torques less what the slipping couplings
pass, and the same system on speeds keeps momentum when couplings lock.  M is
diagonal (one inertia per body) and there are a handful of couplings, so the
system is a few scalars, solved by elimination written out at trace time: one
compiled program for every combination of stuck couplings, vmappable, with no
linear-algebra call.  Couplings that hold the same motion twice (two holds on
one shaft) share it by order: the first takes the torque, the other carries none.

While the modes hold (a pass of the loop) the solution is a fixed linear map
from the bodies' torques tau and the slipping couplings' torques sigma to the
accelerations and the couplings' torques: :class:`Response`, worked out once
per pass, so that each step of the integrator pays a few multiply-adds.
"""

from __future__ import annotations

from functools import cached_property

import jax
import jax.numpy as jnp

from ..._pytree import pytree_dataclass
from .element import STUCK
from .layout import Layout, angle_state


def _absent(g) -> bool:
    """A structural zero: a coupling that does not touch a body, a torque nobody declared."""
    return isinstance(g, float) and g == 0.0


def dot(weights, values):
    """Sum of weight times value, leaving out structural zeros (no term is traced for them)."""
    return sum((w * v for w, v in zip(weights, values) if not (_absent(w) or _absent(v))), 0.0)


# A stuck coupling whose pivot, once the couplings before it are eliminated, is below this fraction of
# its own diagonal holds a motion those couplings already hold (exactly zero but for round-off, some 1e-16).
# Not larger: a hold on a light shaft that a three-shaft linkage ties to heavy ones (1e-9 kg*m^2 against 1 and
# 10) has a pivot 7e-10 of its diagonal, and taken for a motion held twice it would hold nothing.
REDUNDANT_PIVOT = 1e-12


def solve_stuck(matrix, columns, stuck, order=None):
    """Solve the stuck rows of a small symmetric positive-semidefinite system for several right-hand sides.

    ``matrix`` is a list of lists of scalars, each of ``columns`` a list of
    scalars, ``stuck`` a list of booleans; rows and columns of couplings that
    are not stuck become identity rows with a zero right-hand side, so their
    unknowns are zero.  Gaussian elimination without pivoting, in ``order``
    (default: as given), is exact enough here: the masked matrix is positive
    definite unless stuck couplings hold the same motion twice (two holds on
    one shaft).  Then the torque is statically indeterminate: a
    coupling that the ones before it in ``order`` already hold is given none
    (its pivot vanishes but for round-off), and they carry it all.
    """
    n = len(stuck)
    order = list(range(n)) if order is None else list(order)
    a = [[jnp.where(stuck[i] & stuck[j], matrix[i][j], 1.0 if i == j else 0.0) for j in order] for i in order]
    bs = [[jnp.where(stuck[i], column[i], 0.0) for i in order] for column in columns]
    diagonal = [a[i][i] for i in range(n)]
    for k in range(n):
        held = a[k][k] <= REDUNDANT_PIVOT * diagonal[k]
        a[k] = [jnp.where(held, 1.0 if j == k else 0.0, a[k][j]) for j in range(n)]
        for b in bs:
            b[k] = jnp.where(held, 0.0, b[k])
        for i in range(k + 1, n):
            factor = a[i][k] / a[k][k]
            a[i] = [a[i][j] - factor * a[k][j] for j in range(n)]
            for b in bs:
                b[i] = b[i] - factor * b[k]
    out = []
    for b in bs:
        x = [None] * n
        for i in reversed(range(n)):
            x[i] = (b[i] - sum((a[i][j] * x[j] for j in range(i + 1, n)), 0.0)) / a[i][i]
        solved = [None] * n
        for position, i in enumerate(order):
            solved[i] = x[position]
        out.append(solved)
    return out


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
        self.rows = []  # G, one row per coupling over the bodies; 0.0 where it does not touch a body
        for coupling in layout.coupling_elements:
            row = [0.0] * count
            for shaft, weight in coupling.weights():
                body, ratio = layout.shaft(shaft, coupling)
                row[body] = weight * ratio if _absent(row[body]) else row[body] + weight * ratio
            self.rows.append(row)
            sides = coupling.joins()
            if len(sides) == 2:
                a, b = sides
                body_a, ratio_a = layout.shaft(a, coupling)
                body_b, ratio_b = layout.shaft(b, coupling) if b is not None else (None, 0.0)
                self.ends.append((body_a, ratio_a, body_b, ratio_b))
            else:
                self.ends.append(None)

    @cached_property
    def inertia(self) -> list:
        """Each body's inertia: every element's inertia on a shaft of it, times the shaft's ratio squared."""
        inertia = [0.0] * len(self.layout.bodies)
        for element in self.layout.elements:
            for shaft, value in element.inertias():
                body, ratio = self.layout.shaft(shaft, element)
                inertia[body] = inertia[body] + value * ratio**2
        for element, shaft, value, _ in self.varying():
            body, ratio = self.layout.shaft(shaft, element)
            inertia[body] = inertia[body] + value * ratio**2
        return inertia

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
        """The couplings in the order they take a torque that two of them could hold: those that yield last."""
        couplings = self.layout.coupling_elements
        return sorted(range(len(couplings)), key=lambda k: couplings[k].yields)

    def relative(self, k, values):
        """Coupling k's relative speed (or acceleration) for body speeds (or accelerations)."""
        return dot(self.rows[k], values)

    def schur(self):
        """G M^-1 G^T, one entry per pair of couplings."""
        n = len(self.rows)
        return [[sum((gi * gj / m for gi, gj, m in zip(self.rows[i], self.rows[j], self.inertia)
                      if not (_absent(gi) or _absent(gj))), 0.0) for j in range(n)] for i in range(n)]

    def push(self, passed):
        """-G^T T: what the couplings' torques T take from side a and give to side b, per body."""
        out = [0.0] * len(self.inertia)
        for row, p in zip(self.rows, passed):
            out = [f if _absent(g) or _absent(p) else f - g * p for f, g in zip(out, row)]
        return out

    def align(self, values, stuck):
        """Make the values of bodies joined by stuck couplings agree to the last bit.

        Solved in floating point the constraints hold to round-off only; left so,
        two locked shafts would drift apart by ulps a step, and a held shaft would
        creep.  Ground couplings fix their body at zero first; then each stuck
        coupling carries a settled body's value to the other (once per coupling,
        enough for any chain).  A stuck coupling that ties three shafts, after them,
        gives one of its bodies not yet settled the value its relation leaves it:
        the one its row weighs most against its inertia (g^2 / m), whose value the
        solve finds as a small difference of large terms (a light shaft's, drifting
        off the relation and its torque doing work on round-off, else); its bodies
        are settled then.
        """
        values = list(values)
        settled = [jnp.zeros((), bool) for _ in values]
        for end, s in zip(self.ends, stuck):
            if end is not None and end[2] is None:
                body_a = end[0]
                values[body_a] = jnp.where(s, 0.0, values[body_a])
                settled[body_a] = settled[body_a] | s
        for _ in self.ends:
            for end, s in zip(self.ends, stuck):
                if end is None:
                    continue
                body_a, ratio_a, body_b, ratio_b = end
                if body_b is None or body_a == body_b:
                    continue
                to_a = s & settled[body_b] & ~settled[body_a]
                to_b = s & ~to_a & ~settled[body_b]
                values[body_a] = jnp.where(to_a, values[body_b] * (ratio_b / ratio_a), values[body_a])
                values[body_b] = jnp.where(to_b, values[body_a] * (ratio_a / ratio_b), values[body_b])
                settled[body_a] = settled[body_a] | to_a | (s & to_b)
                settled[body_b] = settled[body_b] | to_b | to_a
        for end, row, s in zip(self.ends, self.rows, stuck):
            if end is not None:
                continue
            touched = [j for j, g in enumerate(row) if not _absent(g)]
            given = [dot(row, [0.0 if i == j else v for i, v in enumerate(values)]) for j in touched]
            best, chosen = -1.0, -1
            for j in touched:  # the unsettled body of the largest g^2 / m
                score = row[j] ** 2 / self.inertia[j]
                better = ~settled[j] & (score > best)
                best, chosen = jnp.where(better, score, best), jnp.where(better, j, chosen)
            for j, rest in zip(touched, given):
                values[j] = jnp.where(s & (chosen == j), -rest / row[j], values[j])
            for j in touched:
                settled[j] = settled[j] | s
        return values


@pytree_dataclass
class Response:
    """The bodies' response while the modes hold: a = P tau + Q sigma, T = R tau + U sigma.

    tau: torques on the bodies; sigma: each coupling's sliding torque with the
    sign of its slip (zero unless slipping); a: accelerations; T: the torque
    each coupling passes.  Lists of lists of scalars (a handful of bodies and
    couplings), so that a step evaluates them as plain multiply-adds.  The rows
    of P and Q of bodies joined by stuck couplings are made equal (zero for a
    body held to the ground), so their accelerations agree to the last bit.
    """

    accel_from_torque: list  # P, bodies x bodies
    accel_from_sliding: list  # Q, bodies x couplings
    torque_from_torque: list  # R, couplings x bodies
    torque_from_sliding: list  # U, couplings x couplings


def _divided(values, inertia):
    return [0.0 if _absent(f) else f / m for f, m in zip(values, inertia)]


def solve_response(layout: Layout, stuck, y=None) -> Response:
    """The linear map of :class:`Response` for a set of stuck couplings (one masked solve per unit torque).

    ``y``: the state, where an inertia varies with an angle.
    """
    bodies = Bodies(layout, y)
    nb, nc = len(bodies.inertia), len(bodies.rows)
    never_slips = [not e.can_slip for e in layout.coupling_elements]  # their sigma is always zero

    def unknowns(tau, sigma):
        # right-hand side of the stuck couplings' system for body torques tau and slipping torques sigma
        free = [f if _absent(p) else f + p for f, p in zip(tau, bodies.push(sigma))]
        return [bodies.relative(k, _divided(free, bodies.inertia)) for k in range(nc)]

    inputs = [([1.0 if i == j else 0.0 for i in range(nb)], [0.0] * nc) for j in range(nb)]
    inputs += [([0.0] * nb, [1.0 if i == k and not never_slips[k] else 0.0 for i in range(nc)]) for k in range(nc)]
    held = solve_stuck(bodies.schur(), [unknowns(tau, sigma) for tau, sigma in inputs], stuck, bodies.order)
    accel, torque = [], []
    for (tau, sigma), h in zip(inputs, held):
        passed = [jnp.where(stuck[k], h[k], sigma[k]) for k in range(nc)]
        net = [f if _absent(p) else f + p for f, p in zip(tau, bodies.push(passed))]
        accel.append(bodies.align(_divided(net, bodies.inertia), stuck))
        torque.append(passed)

    def by_rows(values, first, last):
        return [[values[j][i] for j in range(first, last)] for i in range(len(values[0]))] if values else []

    return Response(
        accel_from_torque=by_rows(accel, 0, nb),
        accel_from_sliding=by_rows(accel, nb, nb + nc),
        torque_from_torque=by_rows(torque, 0, nb),
        torque_from_sliding=by_rows(torque, nb, nb + nc),
    )


# Up to this many couplings, the response of every combination of stuck ones is
# solved once per run and looked up during it; beyond, it is solved at each use.
TABULATED_COUPLINGS = 4


class ResponseTable:
    """The response for every stuck set: a matrix, a row per set (row index bit k: coupling k stuck), a
    column per entry of :class:`Response` that is not a structural zero."""

    def __init__(self, matrix, treedef, absent):
        self.matrix, self.treedef, self.absent = matrix, treedef, absent


def response_table(layout: Layout) -> ResponseTable | None:
    """The response for every stuck set, or None if too many couplings.

    One solve, vmapped over the sets (one copy of it in the program).  None too
    where an inertia varies: the response then changes with the state.
    """
    nc = len(layout.couplings)
    if nc > TABULATED_COUPLINGS or layout.inertia_varies:
        return None
    shape = {}

    def solve(bits):
        leaves, shape["treedef"] = jax.tree.flatten(solve_response(layout, [bits[k] for k in range(nc)]))
        shape["absent"] = [_absent(v) for v in leaves]
        return jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in leaves if not _absent(v)] or [jnp.zeros(())])

    sets = jnp.asarray([[bool(index >> k & 1) for k in range(nc)] for index in range(2**nc)]).reshape(2**nc, nc)
    return ResponseTable(jax.vmap(solve)(sets), shape["treedef"], shape["absent"])


def response(layout: Layout, modes, y=None) -> Response:
    """The bodies' response for these modes: picked from ``layout.responses`` when the run tabulated it.

    The pick halves the table on each coupling's stuck bit (a select over whole rows, not a gather:
    under vmap a gather with a per-lane index costs far more).
    """
    stuck = [modes[k] == STUCK for k in range(len(layout.couplings))]
    table = layout.responses
    if table is None:
        return solve_response(layout, stuck, y)
    rows = table.matrix
    for bit in stuck:  # bit k of the table index is coupling k's
        rows = jnp.where(bit, rows[1::2], rows[0::2])
    picked = iter(rows[0][i] for i in range(rows.shape[1]))
    return jax.tree.unflatten(table.treedef, [0.0 if absent else next(picked) for absent in table.absent])


def keep_momentum(layout: Layout, y, stuck):
    """Speeds after the ``stuck`` couplings lock: the nearest in kinetic energy, momentum kept.

    v+ = v - M^-1 G_s^T mu with (G_s M^-1 G_s^T) mu = G_s v: the impulses of the
    locking couplings, and nothing else, change the speeds.
    """
    bodies = Bodies(layout, y)
    if not bodies.rows:
        return y
    speeds = [y[i] for i in range(len(bodies.inertia))]
    rel = [bodies.relative(k, speeds) for k in range(len(bodies.rows))]
    (impulse,) = solve_stuck(bodies.schur(), [rel], stuck, bodies.order)
    speeds = [v + dv / m for v, dv, m in zip(speeds, bodies.push(impulse), bodies.inertia)]
    speeds = bodies.align(speeds, stuck)
    return y.at[: len(speeds)].set(jnp.stack(speeds))

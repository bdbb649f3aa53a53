"""Sums of terms ``coef * u**k * exp(-mu*u)``: the closed form's pieces, their integrals and first roots.

Between two switches every state of the canonical hoist is such a sum in the
local time u (see :mod:`hoistsim.references.exact`); a switch is the first root of one.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq
from scipy.special import gammainc

EPS = float(np.finfo(float).eps)
GRID_POINTS = 4096  # samples per piece when scanning a guard for its first root
NOISE = 1e3 * EPS  # below NOISE * (sum of |terms|) a guard value is rounding, not sign


class ExpPoly:
    """A sum of terms ``coef * u**k * exp(-mu*u)``, keyed by ``(k, mu)``."""

    __slots__ = ("terms",)

    def __init__(self, terms=None):
        self.terms = {key: float(c) for key, c in (terms or {}).items() if c != 0.0}

    @classmethod
    def poly(cls, *coefs):
        return cls({(k, 0.0): c for k, c in enumerate(coefs)})

    @classmethod
    def exp(cls, coef, mu):
        return cls({(0, float(mu)): coef})

    def __add__(self, other):
        other = other if isinstance(other, ExpPoly) else ExpPoly.poly(other)
        terms = dict(self.terms)
        for key, c in other.terms.items():
            terms[key] = terms.get(key, 0.0) + c
        return ExpPoly(terms)

    __radd__ = __add__

    def __neg__(self):
        return ExpPoly({key: -c for key, c in self.terms.items()})

    def __sub__(self, other):
        return self + (-other)

    def __rsub__(self, other):
        return (-self) + other

    def __mul__(self, other):
        if not isinstance(other, ExpPoly):
            return ExpPoly({key: c * other for key, c in self.terms.items()})
        terms = {}
        for (k1, m1), c1 in self.terms.items():
            for (k2, m2), c2 in other.terms.items():
                key = (k1 + k2, m1 + m2)
                terms[key] = terms.get(key, 0.0) + c1 * c2
        return ExpPoly(terms)

    __rmul__ = __mul__

    def _parts(self, u):
        u = np.asarray(u, dtype=float)
        return [c * u**k * np.exp(-mu * u) for (k, mu), c in self.terms.items()] or [0.0 * u]

    def __call__(self, u):
        return sum(self._parts(u))

    def magnitude(self, u):
        """Sum of the terms' absolute values: the scale of the rounding in a value."""
        return sum(np.abs(p) for p in self._parts(u))

    def derivative(self):
        terms = {}
        for (k, mu), c in self.terms.items():
            if k > 0:
                terms[(k - 1, mu)] = terms.get((k - 1, mu), 0.0) + c * k
            if mu != 0.0:
                terms[(k, mu)] = terms.get((k, mu), 0.0) - c * mu
        return ExpPoly(terms)

    def integral(self, u):
        """Definite integral from 0 to u, term by term.

        The incomplete-gamma form keeps full relative accuracy when mu*u is tiny,
        where the textbook antiderivative would cancel catastrophically.
        """
        u = np.asarray(u, dtype=float)
        total = 0.0 * u
        for (k, mu), c in self.terms.items():
            if mu == 0.0:
                total = total + c * u ** (k + 1) / (k + 1)
            else:
                total = total + c * math.factorial(k) / mu ** (k + 1) * gammainc(k + 1, mu * u)
        return total


def first_crossing(guard: ExpPoly, u_end: float):
    """First u in [0, u_end] where ``guard`` goes from positive to <= 0, or None.

    The guard may start exactly on its switching surface (a restart after an
    event).  Values within rounding noise carry no sign, so the start is judged
    by the first probe, on a geometric ladder, whose value stands clear of the
    noise: negative there means the guard leaves the admissible side at once
    (root 0), positive means the search starts from that probe, so the surface
    the piece started on is never found again.
    """
    if u_end <= 0.0:
        return None
    g0 = float(guard(0.0))
    lo = 0.0
    if abs(g0) <= NOISE * float(guard.magnitude(0.0)):
        probes = u_end * 2.0 ** -np.arange(80, -1, -1.0)
        values, noise = guard(probes), NOISE * guard.magnitude(probes)
        clear = np.nonzero(np.abs(values) > noise)[0]
        if clear.size == 0:
            return None  # the guard stays on the surface: nothing to switch
        if values[clear[0]] < 0.0:
            return 0.0
        lo = float(probes[clear[0]])
    elif g0 < 0.0:
        return 0.0
    if lo >= u_end:
        return None
    grid = np.linspace(lo, u_end, GRID_POINTS)
    values = guard(grid)
    slope = guard.derivative()
    slopes = slope(grid)
    # Cells where the guard ends non-positive, or where it has a local minimum
    # (a dip below zero and back inside one cell shows up only there).
    ends_low = values[1:] <= 0.0
    has_min = (slopes[:-1] < 0.0) & (slopes[1:] >= 0.0)
    for i in np.nonzero(ends_low | has_min)[0]:
        if ends_low[i]:
            return _refine(guard, grid[i], grid[i + 1])
        u_min = _refine(slope, grid[i], grid[i + 1]) if slopes[i + 1] > 0.0 else grid[i + 1]
        if guard(u_min) <= 0.0:
            return _refine(guard, grid[i], u_min)
    return None


def _refine(f, a, b):
    if float(f(b)) == 0.0:
        return float(b)
    return float(brentq(lambda u: float(f(u)), a, b, xtol=1e-15, rtol=4 * EPS, maxiter=200))

"""The energy ledger: work done on the machine = kinetic + potential energy + every loss.

Assembled from what the elements declare (``ledger`` and ``ledger_kinds``):
work terms (what a source does), potential terms (a raised mass) and losses
(heat of a slipping coupling), plus the bodies' kinetic energy, which is the
core's.  A run's ledger is evaluated at its first and last state inside the
compiled call; :func:`balance` closes it on the host.
"""

from __future__ import annotations

from .dynamics import Instant
from .layout import Layout


def ledger_values(layout: Layout, y) -> list:
    """Every ledger term at state y, in the order of ``layout.ledger_kinds``."""
    x = Instant(layout, 0.0, y)
    values = {"kinetic_energy": x.kinetic_energy()}
    for element in layout.elements:
        values.update(element.ledger(x))
    return [values[name] for name in layout.ledger_kinds]


def balance(terms: dict) -> dict[str, float]:
    """Changes of every term over the run, the residual and the residual relative to the largest term (J).

    ``terms`` maps each name to (kind, value at the start, value at the end).
    Work terms count what came in, losses what went out, potential (and
    kinetic) terms what is stored; ``residual`` = work - stored - losses.
    """
    out: dict[str, float] = {}
    residual = 0.0
    for name, (kind, start, end) in terms.items():
        change = float(end) - float(start)
        out[f"{name}_change" if kind == "potential" else name] = change
        residual += change if kind == "work" else -change
    scale = max([abs(v) for v in out.values()] + [1e-300])
    out["residual"] = float(residual)
    out["relative_residual"] = float(abs(residual) / scale)
    return out

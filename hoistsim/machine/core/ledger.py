"""The energy ledger: work done on the machine = kinetic + potential energy + every loss.

Assembled from what the elements declare (``ledger`` and ``ledger_kinds``):
work terms (what a source does), potential terms (a raised mass) and losses
(heat of a slipping coupling), plus the bodies' kinetic energy, which is the
core's; and where a loss's heat went (stored, passed to ambient), a ledger of
its own.  A run's ledger is evaluated at its first and last state inside the
compiled call; :func:`balance` closes it on the host.
"""

from __future__ import annotations

import numpy as np

from .dynamics import Instant
from .layout import Layout

HEAT_OF = "heat of "  # the kind of a term that says where a loss went: "heat of " and the loss's name


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
    return {name: float(value) for name, value in balance_columns(terms).items()}


# J: the scale of the residual where every term is smaller (a machine at rest throughout)
STILL = 1e-9
# the kind of a term that is no energy of the ledger but a size of it: the most kinetic energy the machine
# held during the run (the residual's scale where works cancel and the machine ends as it started)
HELD = "held"
PEAK_TERM = "kinetic_energy_peak"


def balance_columns(terms: dict) -> dict[str, np.ndarray]:
    """:func:`balance` for many runs at once: each start and end an array over the runs.

    Terms of kind "heat of <loss>" say where a loss went (stored in a part's
    heat capacity, passed to ambient): they close a ledger of their own against
    that loss, ``heat_residual`` = their sum - the loss (relative to the loss
    in ``heat_relative_residual``), and stay out of the energy residual, where
    the loss already counts.
    """
    out: dict = {}
    residual, heat, held = 0.0, {}, []
    for name, (kind, start, end) in terms.items():
        if kind == HELD:
            held.append(np.abs(np.asarray(end, dtype=float)))
            continue
        if name == "kinetic_energy":  # what the machine holds: a run whose works cancel still turns
            held += [np.abs(np.asarray(start, dtype=float)), np.abs(np.asarray(end, dtype=float))]
        change = np.asarray(end, dtype=float) - np.asarray(start, dtype=float)
        out[f"{name}_change" if kind == "potential" else name] = change
        if kind.startswith(HEAT_OF):
            heat[kind[len(HEAT_OF):]] = heat.get(kind[len(HEAT_OF):], 0.0) + change
            continue
        residual = residual + change if kind == "work" else residual - change
    # relative to the largest term or kinetic energy held; a machine that never moved has none, and its
    # round-off is nothing
    scale = np.max(np.abs(np.asarray([*out.values(), *held, np.full(np.shape(residual), STILL)])), axis=0)
    out["residual"] = np.asarray(residual, dtype=float)
    out["relative_residual"] = np.abs(residual) / scale
    if heat:
        accounted = sum(total - out[loss] for loss, total in heat.items())
        losses = np.max(np.abs(np.asarray([out[loss] for loss in heat] + [np.full(np.shape(accounted), 1e-300)])),
                        axis=0)
        out["heat_residual"] = np.asarray(accounted, dtype=float)
        out["heat_relative_residual"] = np.abs(accounted) / losses
    return out

"""A run's summary (the numbers a designer compares runs by) and many runs' at once, as columns."""

from __future__ import annotations

import numpy as np

from ..machine.core.ledger import balance, balance_columns
from .summaries import Summaries


def summarize(label: str, values: dict, ledger: dict, locks: int, unlocks: int) -> dict:
    """The numbers a designer compares runs by, from the elements' summary values and the ledger.

    Peaks and the lowest load position are exact: the run stops at every slip
    peak and load turnaround (and at every switch) to record them.
    """
    energy = balance(ledger)
    return {
        "label": label,
        **values,
        "lock_events": int(locks),
        "unlock_events": int(unlocks),
        "energy_residual": energy["residual"],
        "energy_relative_residual": energy["relative_residual"],
        **_heat_residual(energy),
    }


def summary_columns(labels: list[str], values: dict, ledger: dict, locks, unlocks) -> dict[str, np.ndarray]:
    """:func:`summarize` for many runs at once: each value an array over the runs, the same numbers."""
    energy = balance_columns(ledger)
    return {
        "label": np.asarray(labels, dtype=object),
        **values,
        "lock_events": np.asarray(locks, dtype=np.int64),
        "unlock_events": np.asarray(unlocks, dtype=np.int64),
        "energy_residual": energy["residual"],
        "energy_relative_residual": energy["relative_residual"],
        **_heat_residual(energy),
    }


def _heat_residual(energy: dict) -> dict:
    """Where a part's heat is followed (stored, passed to ambient), how well it accounts for the loss."""
    return {"heat_relative_residual": energy["heat_relative_residual"]} if "heat_relative_residual" in energy else {}


def ledger_columns(runs) -> dict:
    """The runs' ledgers as one: each term's start and end an array over the runs (for :func:`balance_columns`)."""
    ledgers = [run.ledger for run in runs]
    return {name: (kind, np.asarray([ledger[name][1] for ledger in ledgers], dtype=float),
                   np.asarray([ledger[name][2] for ledger in ledgers], dtype=float))
            for name, (kind, _, _) in ledgers[0].items()}


def summaries_of(runs) -> Summaries:
    """Every run's :attr:`RunResult.summary` at once, the same numbers (each run's ledger closed once, all
    together)."""
    kinds = [list(run.events["kind"]) for run in runs]
    values = {key: np.asarray([run.values[key] for run in runs]) for key in runs[0].values}
    return Summaries(summary_columns([run.label or run.name for run in runs], values, ledger_columns(runs),
                                     [k.count("lock") for k in kinds], [k.count("unlock") for k in kinds]))


"""What loading learns about a scenario beyond its values: where it came from, what it said, its sweep.

Made once, by :func:`hoistsim.scenario.loading.scenario_from_text`, and held by the scenario it
describes (:attr:`hoistsim.scenario.schema.Scenario.provenance`); a sweep's runs hold their own, the
base's with each run's plain data.  Frozen, and plain enough to travel with the scenario to a
cluster's workers (pickled) and through ``model_copy``.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping, Sequence

import numpy as np


@dataclasses.dataclass(frozen=True)
class SweptKey:
    """One swept key's values, as the file gave them (ranges expanded) and as each was checked alone."""

    values: Sequence  # as written, a range's values between its ends in SI numbers
    labels: Sequence[str]  # each value as the user reads it
    numbers: np.ndarray  # each value's SI number (NaN: not a number, a table that varies)
    validated: Sequence  # each value as validated (the key's type): a sweep's runs are built from these


@dataclasses.dataclass(frozen=True)
class Provenance:
    """Where a scenario came from and what loading learned of it that its values do not say."""

    text: str = ""  # the scenario as read, with the command line's overrides and sweep noted
    source: str = "<scenario>"  # the file it was read from (or a name for text and data)
    raw: Mapping = dataclasses.field(default_factory=dict)  # as plain data, before units, overrides applied
    overridden: frozenset[str] = frozenset()  # keys set from the command line (--set)
    warnings: tuple[str, ...] = ()  # values accepted that may not say what was meant (a bare number on a speed)
    swept: Mapping[str, SweptKey] = dataclasses.field(default_factory=dict)  # each swept key, in the sweep's order

    def of_run(self, raw: Mapping) -> Provenance:
        """A run of this scenario's sweep: its plain data ``raw``, no sweep of its own, the rest as here."""
        return Provenance(self.text, self.source, raw, self.overridden, self.warnings, {})

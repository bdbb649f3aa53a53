"""The runs of a sweep without a scenario object per run: built a chunk at a time, on demand.

A sweep is its base scenario and each swept key's values, every value checked
when the file was read (alone, on the validated base: see
:func:`hoistsim.scenario.sweep_spec.with_swept_value`).  Run ``i`` is a position in the
grid of the keys' values (the first key's values slowest); its scenario is
made when it is about to run, so a million runs hold a million values and
labels, never a million scenarios.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from functools import cached_property

import numpy as np

from ..errors import ScenarioError
from .keys import ALTERNATIVES
from .schema import Scenario
from .sweep_spec import held_at, with_swept_value, with_validated_value


class SweepRuns:
    """Every run of ``scenario``'s sweep (one run, the scenario itself, when it has none)."""

    def __init__(self, scenario: Scenario):
        self.base = scenario
        self.keys = list(scenario.sweep or {})
        self.swept = scenario.provenance.swept
        self.shape = tuple(len(self.swept[key].values) for key in self.keys)
        # what every run shares: the base without its sweep (a run is one computation, not a sweep)
        provenance = scenario.provenance
        self._run_base = scenario.model_copy(update={"sweep": None}).with_provenance(
            provenance.of_run({k: v for k, v in provenance.raw.items() if k != "sweep"}))

    def __len__(self) -> int:
        return math.prod(self.shape) if self.keys else 1

    def positions(self, i: int) -> tuple[int, ...]:
        """Run ``i``'s index into each key's values (the last key's fastest)."""
        out = []
        for size in reversed(self.shape):
            i, p = divmod(i, size)
            out.append(p)
        return tuple(reversed(out))

    def positions_of(self, rows: np.ndarray) -> list[np.ndarray]:
        """:meth:`positions` of many runs at once: each key's indices, an array over ``rows``."""
        out, rows = [], np.asarray(rows)
        for size in reversed(self.shape):
            rows, p = np.divmod(rows, size)
            out.append(p)
        return list(reversed(out))

    def label(self, i: int) -> str:
        return ", ".join(f"{key}={self.swept[key].labels[p]}" for key, p in zip(self.keys, self.positions(i)))

    def labels_of(self, rows: np.ndarray) -> np.ndarray:
        """:meth:`label` of many runs at once (an object array of strings)."""
        out = None
        for key, p in zip(self.keys, self.positions_of(rows)):
            own = np.asarray([f"{key}={label}" for label in self.swept[key].labels], dtype=object)[p]
            out = own if out is None else out + ", " + own
        return out

    @property
    def labels(self) -> "Labels":
        """Every run's label, made when read (a million runs keep their values' labels, not a million more)."""
        return Labels(self)

    def __getstate__(self) -> dict:
        # sent to a cluster's workers: what builds the runs, not what is derived from it
        return {k: v for k, v in self.__dict__.items() if k != "parameters"}

    @cached_property
    def parameters(self) -> dict[str, np.ndarray]:
        """Swept key -> its SI value in each run (NaN for a table that varies)."""
        grids = np.meshgrid(*(self.swept[key].numbers for key in self.keys), indexing="ij")
        return {key: grid.ravel() for key, grid in zip(self.keys, grids)}

    def scenario(self, i: int) -> Scenario:
        """Run ``i``'s scenario, validated (its values were checked as the file was read)."""
        if not self.keys:
            return self.base
        run = self._run_base
        raw = dict(run.provenance.raw)
        for key, p in zip(self.keys, self.positions(i)):
            value = self.swept[key].values[p]
            if _in_sections(run, key):  # as validated when read (its checks, and every combination's, passed)
                run = with_validated_value(run, key, self.swept[key].validated[p])
            else:  # a key in a section the sweep adds: validated again
                run = with_swept_value(run, key, value, raw)
            _assign_copied(raw, key, value)
        return run.with_provenance(self._run_base.provenance.of_run(raw))


def _in_sections(scenario: Scenario, key: str) -> bool:
    """Whether every section on a key's path is there (sections, parts by name, a list's members)."""
    holder = key.rpartition(".")[0]
    return not holder or held_at(scenario, holder) is not None


class Labels(Sequence):
    """The labels of a sweep's runs, each made from its values' labels when read."""

    def __init__(self, runs: SweepRuns):
        self.runs = runs

    def __len__(self) -> int:
        return len(self.runs)

    def __getitem__(self, index):
        if isinstance(index, slice):
            return [self.runs.label(i) for i in range(*index.indices(len(self)))]
        if index < 0:
            index += len(self)
        if not 0 <= index < len(self):
            raise IndexError(index)
        return self.runs.label(index)

    def __eq__(self, other) -> bool:
        return isinstance(other, Sequence) and list(self) == list(other)

    def __repr__(self) -> str:
        return f"Labels({len(self)} runs: {self[0]!r}, ...)"


def sweep_values(scenario: Scenario) -> list[tuple[str, Scenario]]:
    """One (label, scenario) per run: the sweep's values, a grid when two keys are swept.

    A scenario per run, all at once: for a few runs (a large sweep builds its runs
    a chunk at a time, :class:`hoistsim.scenario.sweep_runs.SweepRuns`).
    """
    runs = SweepRuns(scenario)
    return [(runs.label(i), runs.scenario(i)) for i in range(len(runs))]


def _assign_copied(raw: dict, key: str, value) -> None:
    """Set a dotted key in plain data, copying only the mappings on its path (the rest is shared)."""
    *path, leaf = key.split(".")
    node = raw
    for part in path:
        node[part] = dict(node.get(part) or {})
        node = node[part]
    node[leaf] = value
    for other in ALTERNATIVES.get(key, ()):
        node.pop(other, None)


def check_combinations(scenario: Scenario) -> None:
    """With two keys swept, each value was checked alone; checks across keys see every combination."""
    runs = SweepRuns(scenario)
    for i in range(len(runs)):
        try:
            runs.scenario(i)
        except ScenarioError as exc:
            exc.message = f"{exc.message} (in sweep run {runs.label(i)})"
            exc.source = scenario.source
            raise

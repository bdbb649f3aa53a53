"""The summaries of many runs as columns: what a results file holds for a sweep, read without JAX."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np


class Summaries(Sequence):
    """The summaries of many runs, kept as columns (a million runs: a few arrays, not a million dicts).

    Indexed by run, it reads as the summary dicts of :func:`summarize`; ``columns``
    maps each name (label included) to its values over the runs.
    """

    def __init__(self, columns: dict[str, np.ndarray]):
        self.columns = columns

    @classmethod
    def from_rows(cls, rows: list[dict]) -> "Summaries":
        return cls({key: np.asarray([row[key] for row in rows], dtype=object if key == "label" else None)
                    for key in rows[0]})

    @classmethod
    def concatenate(cls, parts: list["Summaries"]) -> "Summaries":
        return cls({key: np.concatenate([p.columns[key] for p in parts]) for key in parts[0].columns})

    def __len__(self) -> int:
        return len(self.columns["label"])

    def __getitem__(self, index):
        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        return {key: values[index].item() if hasattr(values[index], "item") else values[index]
                for key, values in self.columns.items()}

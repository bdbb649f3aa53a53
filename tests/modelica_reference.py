"""Modelica's published reference trajectories (tests/data/modelica/, from modelica/MAP-LIB_ReferenceResults; its
source in SOURCE.md) and how far a run is from them: what the tests of the Modelica examples share.  The reading,
the measure and each example's comparison signals are the package's (:mod:`hoistsim.references.dymola`,
:mod:`hoistsim.references.modelica_signals`), which the documentation's gallery reads too."""

from __future__ import annotations

import numpy as np
from helpers import TESTS

from hoistsim.references import dymola
from hoistsim.references.dymola import events as events
from hoistsim.references.modelica_signals import COMPARISONS

DATA = TESTS / "data" / "modelica"


def reference(example: str) -> dict:
    """The example's reference trajectories: signal -> its column (``time`` among them); ``<Example>.csv``, or
    ``.csv.gz`` for the larger ones (the same file, compressed)."""
    return dymola.read_reference(DATA, example)


def deviations(run, example: str, ours: dict, until: float = np.inf) -> dict:
    """Each comparison signal's worst deviation from the reference, over its range, at every reference row more
    than 1 ms from a reference event (``ours``: signal -> our series on the run's rows), before ``until`` (s)."""
    return dymola.deviations(run.time, reference(example), ours, until)


def signals(example: str, run) -> dict:
    """The example's comparison signals from ``run`` (``translational/<Example>`` for a Translational one)."""
    return COMPARISONS[example].signals(run)

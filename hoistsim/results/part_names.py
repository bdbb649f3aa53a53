"""A run read back under its parts' own names: what the parts' displays read.

A hoist's results keep the names its users know (``slip_speed``, ``lockup_time``) for what its drawn parts call
``clutch_slip`` and ``clutch_lockup_time``; the scenario's lowering says which (its names table, from the
scenario's values the file keeps), and which drawn parts the runs speak of.
"""

from __future__ import annotations

import numpy as np

from ..display.part_names import under_part_names
from ..scenario.lowering import drawn_parts, output_names


def names_table(parameters: dict) -> dict:
    """A run's parts' output names -> those its file keeps them under (None: not kept), from the scenario's
    resolved values (a file's ``parameters``); {} for a drawn drivetrain's, whose names are its parts'."""
    return output_names(parameters)


def with_part_names(run: dict, parameters: dict) -> dict:
    """``run`` (a dict as :func:`.reading.read_runs` gives) with ``names`` (its names table) and ``parts`` (the
    drawn parts it speaks of, by kind and name) put in, and its columns and summary values also under its parts'
    names."""
    names = names_table(parameters)
    run.update(under_part_names({key: value for key, value in run.items() if isinstance(value, np.ndarray)}, names))
    if "attrs" in run:
        run["attrs"] = under_part_names(run["attrs"], names)
    run["names"], run["parts"] = names, drawn_parts(parameters)
    return run

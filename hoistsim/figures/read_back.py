"""A run read back for the figures: its scenario's values (a sweep's run with its own put in), the drawn parts it
speaks of, and its columns and summary under its parts' own names beside those its file keeps them under (a
hoist's ``slip_speed`` is its clutch's ``clutch_slip`` too): what the parts' displays read."""

from __future__ import annotations

import json

import numpy as np

from ..results.part_names import with_part_names


def prepared(run: dict) -> dict:
    """``run`` (a dict as :func:`hoistsim.results.reading.read_runs` gives) with ``parameters``, ``names`` (its
    parts' names -> those its file keeps) and ``parts`` (the drawn parts it speaks of) put in, and its columns and
    summary values also under its parts' names (:mod:`hoistsim.results.part_names`)."""
    return run if "parts" in run else with_part_names(run, parameters_of(run))


def parameters_of(run: dict) -> dict:
    """The run's scenario in SI numbers: the file's base, with this run's swept values put in."""
    if "parameters" not in run:
        parameters = json.loads(run["attrs"]["parameters"])
        for key, value in run["attrs"].items():  # a swept scalar: "clutch_heating.max_temperature"
            *sections, last = key.split(".")
            holder = parameters
            for section in sections:
                holder = holder.get(section) if isinstance(holder, dict) else None
            if sections and isinstance(holder, dict) and np.ndim(value) == 0 and np.isfinite(value):
                holder[last] = float(value)
        run["parameters"] = parameters
    return run["parameters"]

"""A run's values under its parts' own names: what the displays read.

A hoist's results keep the names its users know (``slip_speed``, ``lockup_time``) for what the machine's parts
call ``clutch_slip`` and ``clutch_lockup_time``; a run's names table (part's name -> the name written, from the
scenario's lowering) puts each value in under its part's name too, so one display draws a clutch whatever the
scene that named it.
"""

from __future__ import annotations


def under_part_names(values: dict, names: dict) -> dict:
    """``values`` (columns, or a summary) with each one a part names otherwise also under the part's name."""
    added = {part: values[written] for part, written in names.items()
             if written is not None and written in values and part not in values}
    return {**values, **added} if added else values


def part_names_of(names: dict) -> dict:
    """Each written name the table renames -> its part's name (to choose the columns a display reads)."""
    return {written: part for part, written in names.items() if written is not None}

"""A scenario lowered to the drawn drivetrain's parts the machine builds: the one place that walks a scenario for
them.

A drawn drivetrain's parts are its own, found under the machine's registry paths (``drivetrain.clutches.*``); a
hoist's are the parts its template writes out (:data:`.hoist_template.TEMPLATE`), each with the template's part
that writes it; both in the registry's order.  The machine maps a part's path to its element and knows nothing of
the hoist's sections; the names a hoist's results are written under are applied when they are written
(:func:`output_names`).
"""

from __future__ import annotations

from typing import NamedTuple

from .hoist_template import TEMPLATE, TemplatePart, section_of
from .steady_lift import with_steady_lift
from .sweep_spec import held_at


class Part(NamedTuple):
    """One part of the machine a scenario names, written out as the drawn drivetrain's part it is."""

    section: str  # its dotted place in the scenario (drivetrain.clutches.c; a hoist's section: clutch)
    spec: object  # its drawn spec, standing alone (a key within a part, its rope: the part that holds it)
    path: str  # its registry path (drivetrain.clutches.*)
    held: object  # the spec that picks its variant: the part, or the key within it
    source: tuple  # where the section it is written from is in the scenario (names, a list's index)
    template: TemplatePart | None  # a hoist's section: the template's part that writes it out


class Lowered(NamedTuple):
    """A scenario lowered: the scenario its parts are written out from, and the parts (the names its results are
    written under where they are not the parts' own: :func:`output_names`)."""

    scenario: object  # the scenario as loaded, a hoist started at its steady lift (initial.steady_lift)
    parts: list


def lower(scenario, paths) -> Lowered:
    """``scenario`` lowered to its parts (:func:`lowered_parts`), a hoist's started at its steady lifting speed
    where ``initial.steady_lift`` asks (:func:`.steady_lift.with_steady_lift`)."""
    scenario = with_steady_lift(scenario)
    return Lowered(scenario, lowered_parts(scenario, paths))


def output_names(scenario) -> dict:
    """The names a scenario's results are written under where they are not its parts' own: a hoist's, those its
    users know (``slip_speed`` for its clutch's ``clutch_slip``; None: an output the hoist does not write); none
    for a drawn drivetrain.  The machine runs under the parts' names, so a hoist and the drivetrain it stands
    for are one program.  ``scenario`` may be the resolved values a results file keeps."""
    if section_of(scenario, ("drivetrain",)) is not None:
        return {}
    return {name: hoist for _, parts, part in _TEMPLATE_PARTS if section_of(scenario, parts) is not None
            for name, hoist in part.names.items()}


def drawn_parts(parameters: dict) -> dict:
    """The drawn parts a run's results speak of, by kind and name (``{"clutches": {"clutch": {...}}}``), from the
    scenario's resolved values (what a results file keeps): a drawn drivetrain's own, a hoist's as its template
    names them, each with its hoist section's values."""
    drawn = parameters.get("drivetrain")
    if drawn is not None:
        return drawn
    parts: dict = {}
    for _, sections, part in _TEMPLATE_PARTS:
        spec = section_of(parameters, sections) if part.name else None
        if spec is not None:
            parts.setdefault(part.path.split(".")[1], {})[part.name] = spec
    return parts


def lowered_parts(scenario, paths) -> list[Part]:
    """Each part ``scenario`` names, written out, in the order of ``paths`` (the machine's registry): a drawn
    drivetrain's with what it needs of the scenario written in, a hoist's sections as its template writes them
    out (a section that stands for several parts: a part each; parts under one path in the template's order).
    One order for every machine: a hoist and the drivetrain it stands for are one program."""
    if scenario.drivetrain is None:  # in the registry's order as a drawn drivetrain's (the template's within a path)
        order = {path: rank for rank, path in enumerate(paths)}
        return sorted([_part(section, parts, part.path, part.as_drawn(spec, scenario), part) for section, parts, part
                       in _TEMPLATE_PARTS if (spec := section_of(scenario, parts)) is not None],
                      key=lambda part: order.get(part.path, 0))
    return [_part(section, source, path, _lowered(spec, scenario), None) for path in paths
            for section, source, spec in _parts_of(scenario, tuple(path.split(".")))]


def lowered_again(part: Part, scenario) -> Part:
    """``part`` written out again from another scenario (a sweep's run: its own values in the same sections)."""
    section = held_at(scenario, ".".join(part.source))
    spec = _lowered(section, scenario) if part.template is None else part.template.as_drawn(section, scenario)
    return _part(part.section, part.source, part.path, spec, part.template)


def _part(section: str, source: tuple, path: str, spec, template) -> Part:
    parts = path.split(".")
    held = getattr(spec, parts[-1]) if within_part(parts) else spec
    return Part(section, spec, path, held, source, template)


def _lowered(spec, scenario):
    """A drawn part's spec as its element reads it: standing alone, with what it needs of the scenario written
    in (a load's gravity and starting speed: :meth:`~.schema_load.LoadOnShaftSpec.lowered`)."""
    lowered = getattr(spec, "lowered", None)
    return spec if lowered is None else lowered(scenario)


def within_part(parts: tuple) -> bool:
    """Whether a registry path names a key within a part (drivetrain.motors.*.ripple, drivetrain.load.rope):
    built from the part that holds it."""
    return len(parts) > 2 and parts[-1] != "*"


# each hoist section's drawn parts: (section, its path split, the part)
_TEMPLATE_PARTS = [(section, tuple(section.split(".")), part) for section, parts in TEMPLATE.items() for part in parts]


def _parts_of(scenario, parts: tuple) -> list:
    """(dotted section, where the spec that builds it is, that spec) of each part a registry path names:
    drivetrain.clutches.* gives drivetrain.clutches.<name> for each clutch, drivetrain.torques.*
    drivetrain.torques.<index>.  A key within a part (drivetrain.motors.*.ripple, drivetrain.load.rope) is
    built from the part that holds it (its element reads its keys there), where it is given."""
    found = [((), scenario, None)]
    for part in parts:
        if part == "*":
            found = [((*where, str(key)), member, holder) for where, holder, _ in found
                     for key, member in (holder.items() if isinstance(holder, dict) else enumerate(holder))]
        else:
            found = [((*where, part), getattr(holder, part, None), holder) for where, holder, _ in found]
            found = [(where, member, holder) for where, member, holder in found if member is not None]
    if within_part(parts):
        return [(".".join(where), where[:-1], holder) for where, _, holder in found]
    return [(".".join(where), where, member) for where, member, _ in found]

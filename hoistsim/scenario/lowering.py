"""A scenario lowered to the drawn drivetrain's parts the machine builds: the one place that walks a scenario for
them.

A drawn drivetrain's parts are its own, found under the machine's registry paths (``drivetrain.clutches.*``) in
the registry's order; a hoist's are the parts its template writes out (:data:`.hoist_template.TEMPLATE`), in the
template's order, each with the template's part that writes it.  The machine maps a part's path to its element
and knows nothing of the hoist's sections.
"""

from __future__ import annotations

from typing import NamedTuple

from .hoist_template import TEMPLATE, TemplatePart, section_of
from .steady_lift import with_steady_lift


class Part(NamedTuple):
    """One part of the machine a scenario names."""

    section: str  # its dotted place in the scenario (drivetrain.clutches.c; a hoist's section: clutch)
    spec: object  # the spec its element is built from (a key within a part, its rope: the part that holds it)
    path: str  # its registry path (drivetrain.clutches.*)
    held: object  # the spec that picks its variant: the part, or the key within it (a hoist's: its section)
    template: TemplatePart | None  # a hoist's section: the template's part that writes the drawn part out


class Lowered(NamedTuple):
    """A scenario lowered: the scenario its parts are written out from, and the parts."""

    scenario: object  # the scenario as loaded, a hoist started at its steady lift (initial.steady_lift)
    parts: list


def lower(scenario, paths) -> Lowered:
    """``scenario`` lowered to its parts (:func:`lowered_parts`), a hoist's started at its steady lifting speed
    where ``initial.steady_lift`` asks (:func:`.steady_lift.with_steady_lift`)."""
    scenario = with_steady_lift(scenario)
    return Lowered(scenario, lowered_parts(scenario, paths))


def lowered_parts(scenario, paths) -> list[Part]:
    """Each part ``scenario`` names, in order: a drawn drivetrain's under ``paths`` (the machine's registry, in
    its order), a hoist's sections as its template writes them out (a section that stands for several parts:
    a part each)."""
    if scenario.drivetrain is None:
        return [Part(section, spec, part.path, spec, part) for section, parts, part in _TEMPLATE_PARTS
                if (spec := section_of(scenario, parts)) is not None]
    return [Part(section, _lowered(spec, scenario), path, held, None) for path in paths
            for section, spec, held in _parts_of(scenario, tuple(path.split(".")))]


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
    """(dotted section, the spec that builds it, the part itself) of each part a registry path names:
    drivetrain.clutches.* gives drivetrain.clutches.<name> for each clutch, drivetrain.torques.*
    drivetrain.torques.<index>.  A key within a part (drivetrain.motors.*.ripple, drivetrain.load.rope) is
    built from the part that holds it (its element reads its keys there), where it is given."""
    found = [("", scenario, None)]
    for part in parts:
        if part == "*":
            found = [(f"{where}.{key}", member, holder) for where, holder, _ in found
                     for key, member in (holder.items() if isinstance(holder, dict) else enumerate(holder))]
        else:
            found = [(f"{where}.{part}" if where else part, getattr(holder, part, None), holder)
                     for where, holder, _ in found]
            found = [(where, member, holder) for where, member, holder in found if member is not None]
    within = within_part(parts)
    return [(where, holder if within else member, member) for where, member, holder in found]

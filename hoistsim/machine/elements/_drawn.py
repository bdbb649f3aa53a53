"""A hoist section built as the drawn drivetrain's part its template writes out: one element class for a part,
in either form."""

from __future__ import annotations

from dataclasses import dataclass

from ...scenario.lowering import within_part


@dataclass(frozen=True, eq=False)  # each part its own key of the cache
class Drawn:
    """A hoist section's drawn part (:class:`hoistsim.scenario.hoist_template.TemplatePart`): its template writes
    out the part's spec, from which the registry's ``entry`` for its path builds the element as it does for a
    drawn drivetrain (a key within a part, its rope or its ripple: from the part that holds it).

    The runs of a sweep share every section they do not sweep (the same objects), so the element last built
    here serves again while its section and what the part ``reads`` are the very objects it was built from: a
    run's plan is not paid for a part that is the same in every run.  tests/machine/test_elements.py holds
    ``reads`` to what the template and the element read.
    """

    part: object  # TemplatePart
    entry: object  # the registry's: an element class, or the variant's name -> class
    held: str | None = None  # a key within the part (its path's last) whose spec picks the variant, or None

    def from_spec(self, spec, scenario):
        read = tuple(getattr(scenario, name) for name in self.part.reads)
        last = _LAST_BUILT.get(self)
        if last is not None and last[0] is spec and all(a is b for a, b in zip(last[1], read)):
            return last[2]
        drawn = self.part.as_drawn(spec, scenario)
        held = drawn if self.held is None else getattr(drawn, self.held)
        element = element_of(self.entry, held).from_spec(drawn, scenario)
        _LAST_BUILT[self] = (spec, read, element)  # the objects it was built from held: never mistaken for others
        return element

    @classmethod
    def of(cls, part, registry: dict) -> "Drawn":
        """The drawn part ``part`` with its path's entry in ``registry`` (its path split once, here)."""
        parts = tuple(part.path.split("."))
        return cls(part, registry[part.path], parts[-1] if within_part(parts) else None)


def element_of(entry, spec):
    """The element class a registry entry builds for a part: its variant's (its spec's ``characteristic``), for
    an entry with variants."""
    return entry[spec.characteristic] if isinstance(entry, dict) else entry


_LAST_BUILT: dict = {}  # Drawn part -> (its section, what it read, the element built from them)

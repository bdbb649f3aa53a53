"""A hoist section built as a drawn drivetrain's part: one element class for a part, in either form."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Drawn:
    """The registry's entry for a hoist section that the hoist's template writes out as a drawn part
    (:mod:`hoistsim.scenario.hoist_template`): ``as_drawn(spec, scenario)`` gives the part's spec, from which
    ``element`` builds as it does for a drawn drivetrain.

    ``reads``: what else of the scenario the two read (its sections by name).  The runs of a sweep share
    every section they do not sweep (the same objects), so the element last built here serves again while its
    section and what it reads are the very objects it was built from: a run's plan is not paid for a part
    that is the same in every run.  tests/machine/test_elements.py holds ``reads`` to what they read.
    """

    element: type
    as_drawn: Callable
    reads: tuple[str, ...] = ()

    def from_spec(self, spec, scenario):
        read = tuple(getattr(scenario, name) for name in self.reads)
        last = _LAST_BUILT.get(self)
        if last is not None and last[0] is spec and all(a is b for a, b in zip(last[1], read)):
            return last[2]
        element = self.element.from_spec(self.as_drawn(spec, scenario), scenario)
        _LAST_BUILT[self] = (spec, read, element)  # the objects it was built from held: never mistaken for others
        return element


_LAST_BUILT: dict = {}  # Drawn entry -> (its section, what it read, the element built from them)

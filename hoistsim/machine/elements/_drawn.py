"""A hoist section built as a drawn drivetrain's part: one element class for a part, in either form."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass


@dataclass(frozen=True)
class Drawn:
    """The registry's entry for a hoist section that the hoist's template writes out as a drawn part
    (:mod:`hoistsim.scenario.hoist_template`): ``as_drawn(spec, scenario)`` gives the part's spec, from which
    ``element`` builds as it does for a drawn drivetrain."""

    element: type
    as_drawn: Callable

    def from_spec(self, spec, scenario):
        return self.element.from_spec(self.as_drawn(spec, scenario), scenario)

"""The structure of a machine, read from its elements: bodies, shafts, couplings, states, kinds.

Built at trace time from the plan's elements (cheap: a few dictionaries), so
the structure always follows the elements a scene names.  Names are the only
way in: ``state_index(name)``, ``coupling_index(section)``,
``shaft(name)``.
"""

from __future__ import annotations

import copy

from ...switch_kinds import SWITCH_KINDS
from .element import AbstractCoupling

LOCK, UNLOCK, REVERSAL, ENGAGE, DISENGAGE = range(5)
NO_EVENT = -1


def angle_state(shaft: str) -> str:
    """The name of a shaft's angle, as a state and as an output column."""
    return f"{shaft}_angle"


class LayoutError(ValueError):
    """Elements that do not fit together; ``key`` names the scenario key to blame."""

    def __init__(self, key: str, message: str):
        super().__init__(message)
        self.key = key


def _outputs(elements: tuple, angle_columns: dict) -> tuple[dict, dict]:
    """(columns, summaries) of the elements and the angles read: name -> (units, description), name -> units.

    A results file holds every series and every summary side by side, each under its name: a name is made by
    one element only, and is a series or a summary, never both (else a series of rows would be written where
    a summary's one value is, or one element's values over another's).  Checked as the names are made, once
    for a layout, whatever the elements."""
    columns, summaries = {}, {}
    made = {}  # name -> (the maker's place in the elements, its section, "series" or "summary")
    angles = {name: (units, text) for name, units, text in angle_columns.values()}
    makers = [(e.section, e.columns, e.summaries) for e in elements] + [("the angles read", angles, {})]
    for place, (section, series, summary) in enumerate(makers):
        for kind, names, into in (("series", series, columns), ("summary", summary, summaries)):
            for name, value in names.items():
                if name in made:
                    by, by_section, was = made[name]
                    said = f"both a {was} and a {kind} of {section!r}" if by == place \
                        else f"a {was} of {by_section!r} and a {kind} of {section!r}"
                    raise LayoutError(section, f"output {name!r} is {said}: each output needs a name of its own")
                made[name] = (place, section, kind)
                into[name] = value
    return columns, summaries


class Layout:
    """Bodies, shafts, couplings, named states and event kinds of a tuple of elements."""

    def __init__(self, elements: tuple):
        self.elements = elements
        self.bodies: list[str] = []
        self.body_speeds: list = []
        self.shafts: dict[str, tuple[int, object]] = {}  # shaft -> (body index, speed ratio to the body)
        # a shaft a part declares on another, of which it is a part (a point on its rim) -> that other
        self.parents: dict[str, str] = {}
        for element in elements:
            for body, speed in element.bodies().items():
                self._new_shaft(element, body, (len(self.bodies), 1.0))
                self.bodies.append(body)
                self.body_speeds.append(speed)
            for shaft, (parent, ratio) in element.shafts().items():
                body, factor = self.shaft(parent, element)
                self._new_shaft(element, shaft, (body, factor * ratio))
                if element.shafts_are_parts:
                    self.parents[shaft] = parent
        self.couplings = [i for i, e in enumerate(elements) if isinstance(e, AbstractCoupling)]
        self.coupling_names = [elements[i].section for i in self.couplings]
        self.state_names = [f"{body}.speed" for body in self.bodies]
        self.initial_states: list = list(self.body_speeds)
        for element in elements:
            for name, value in element.states().items():
                if name in self.state_names:
                    raise LayoutError(element.section, f"state {name!r} is declared twice")
                self.state_names.append(name)
                self.initial_states.append(value)
        # angles: a state only for a shaft some element reads the angle of
        self.angle_shafts = []
        for element in elements:
            for shaft in element.angles():
                self.shaft(shaft, element)
                if shaft not in self.angle_shafts:
                    self.angle_shafts.append(shaft)
        self.state_names += [angle_state(shaft) for shaft in self.angle_shafts]
        # each angle's column: <shaft>_angle (rad), or what the element a shaft is calls it (a mass's position)
        named = {shaft: column for element in elements for shaft, column in element.angle_columns().items()}
        self.angle_columns = {shaft: named.get(shaft, (angle_state(shaft), "rad", f"angle of the {shaft} shaft "
                                                       "(its initial angle at t = 0)")) for shaft in self.angle_shafts}
        starts = {shaft: angle for element in elements for shaft, angle in element.angle_starts().items()}
        self.initial_states += [starts.get(shaft, 0.0) for shaft in self.angle_shafts]
        self._state_index = {name: i for i, name in enumerate(self.state_names)}
        self.event_kinds = list(SWITCH_KINDS)
        # kinds of mode changes: the core's, those couplings rename them to, the crossings named by their way
        self.switch_kinds = list(SWITCH_KINDS)
        for element in elements:
            named = [*getattr(element, "switch_names", {}).values(),
                     *(k for pair in element.crossing_events.values() for k in pair)]
            self.switch_kinds += [k for k in named if k not in self.switch_kinds]
        self.event_kinds = list(self.switch_kinds)
        for element in elements:
            self.event_kinds += [k for k in element.event_kinds if k not in self.event_kinds]
        # kinks that close a cycle: (element index, kink, event kind)
        self.cycles = [(i, kink, kind) for i, e in enumerate(elements) for kink, kind in e.cycles.items()]
        self.event_kinds += [kind for _, _, kind in self.cycles if kind not in self.event_kinds]
        self.inertia_varies = any(e.inertia_varies for e in elements)
        self.observation_kinds = ["slip_peak"] if any(e.can_slip and e.observes_slip_peak
                                                      for e in self.coupling_elements) else []
        for element in elements:
            self.observation_kinds += [k for k in element.observation_kinds
                                       if k not in self.observation_kinds and k not in element.crossing_events]
        self.event_kinds += [k for k in self.observation_kinds if k not in self.event_kinds]
        self.sections = [e.section for e in elements]
        # guards and events find their element by its name: one that has them has a name of its own (an element
        # that watches nothing may share one: a torque source named after the shaft it turns)
        for element in elements:
            watched = (isinstance(element, AbstractCoupling) or element.observation_kinds or element.cycles
                       or element.kink_names() or element.event_kinds)
            if watched and self.sections.count(element.section) > 1:
                raise LayoutError(element.section, f"{element.section!r} names more than one part of the machine, "
                                  "and this one's guards and events are found by its name")
        self._columns, self.summaries = _outputs(elements, self.angle_columns)
        # where the loop writes each output among its own (all of them, in this order; see named)
        self.column_slots = list(range(len(self._columns)))
        self.summary_slots = list(range(len(self.summaries)))
        self.summary_count = len(self.summaries)
        self._names: dict = {}  # the names it reads back under (see named)
        self.ledger_kinds = {"kinetic_energy": "potential"}
        self.ledger_kinds.update({name: kind for e in elements for name, kind in e.ledger_kinds.items()})

    def _new_shaft(self, element, name, where):
        if name in self.shafts:
            raise LayoutError(element.section, f"shaft {name!r} is declared twice")
        self.shafts[name] = where

    def shaft(self, name: str, element=None) -> tuple[int, object]:
        """(body index, speed ratio) of a shaft: its speed is the ratio times the body's."""
        try:
            return self.shafts[name]
        except KeyError:
            who = element.section if element is not None else "machine"
            known = ", ".join(self.shafts) or "none"
            raise LayoutError(f"{who}.shaft", f"there is no shaft {name!r} in this machine (shafts: {known})") \
                from None

    def with_parts(self, shafts: tuple) -> tuple:
        """``shafts`` and every shaft a part declares as a part of one of them (``shafts_are_parts``), of those in
        turn, and so on: a point on a shaft's rim, and a body tied to it, are of the shaft, and what acts on them
        is taken by it.  (A drawn shaft tied to the first of its train is no part of it.)"""
        found = list(shafts)
        for shaft in found:  # grows as it goes
            found += [child for child, parent in self.parents.items() if parent == shaft and child not in found]
        return tuple(found)

    @property
    def coupling_elements(self) -> list:
        return [self.elements[i] for i in self.couplings]

    def state_index(self, name: str) -> int:
        return self._state_index[name]

    def coupling_index(self, section: str) -> int:
        return self.coupling_names.index(section)

    def kind_code(self, kind: str) -> int:
        return self.event_kinds.index(kind)

    def switch_code(self, coupling, core_kind: int) -> int:
        """The event kind a coupling records for one of the core's switch kinds (renamed by ``switch_names``)."""
        name = SWITCH_KINDS[core_kind]
        return self.kind_code(coupling.switch_names.get(name, name))

    @property
    def size(self) -> int:
        return len(self.state_names)

    def columns(self) -> dict[str, tuple[str, str]]:
        """Every output column of the machine: name -> (units, description), in element order."""
        return self._columns

    def named(self, names: dict) -> Layout:
        """This layout with its outputs under the names a scenario writes its results under (``names``: an
        output's, event kind's, ledger term's or state's name -> the scenario's; None: an output not written),
        for reading a run back.  The loop writes its arrays in the elements' order, under whatever names: one
        program serves every scenario that names the same machine's outputs otherwise."""
        if not names:
            return self
        named = copy.copy(self)
        named._names = dict(names)
        columns = [(slot, names.get(name, name), value) for slot, (name, value) in enumerate(self._columns.items())]
        named._columns = {name: value for _, name, value in columns if name is not None}
        named.column_slots = [slot for slot, name, _ in columns if name is not None]
        summaries = [(slot, names.get(name, name), units) for slot, (name, units) in enumerate(self.summaries.items())]
        named.summaries = {name: units for _, name, units in summaries if name is not None}
        named.summary_slots = [slot for slot, name, _ in summaries if name is not None]
        for kinds in ("event_kinds", "switch_kinds", "observation_kinds", "state_names"):
            setattr(named, kinds, [names.get(kind, kind) for kind in getattr(self, kinds)])
        named.ledger_kinds = {names.get(term, term): kind for term, kind in self.ledger_kinds.items()}
        named._state_index = {name: i for i, name in enumerate(named.state_names)}
        named.cycles = [(i, kink, names.get(kind, kind)) for i, kink, kind in self.cycles]
        return named

    def name(self, name: str) -> str:
        """What an element's output, event kind or term ``name`` is read back as (:meth:`named`)."""
        return self._names.get(name, name)

    def column_slot(self, name: str) -> int:
        """Where the loop writes the output column ``name`` (as read back) among its columns."""
        return self.column_slots[list(self._columns).index(name)]

    def summary_slot(self, name: str) -> int:
        """Where the loop writes the summary ``name`` (as read back) among its summaries."""
        return self.summary_slots[list(self.summaries).index(name)]

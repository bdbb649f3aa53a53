"""What a part of the machine may bring to a run: the element and coupling interfaces.

An element is a frozen dataclass whose fields are its traced numbers (a new
value never recompiles); fields declared ``static()`` are structure (a shaft's
name).  Everything an element contributes is optional and empty by default, so
an element the scene does not name contributes nothing at all: no body, no
state, no term, no guard, no column.

Elements speak of *shafts*: a body (a rigid shaft with a speed of its own in
the state) or a shaft tied rigidly to one (its speed a fixed multiple of the
body's).  Inertia and torque on a shaft are brought to its body by equal
kinetic energy and equal power, the seed's reduced system.

Contributions, all read at trace time (``x`` is the machine at one instant,
:class:`hoistsim.machine.core.dynamics.Instant`):
- ``bodies()``: new bodies, name -> initial speed (rad/s);
- ``shafts()``: new shafts tied to others, name -> (shaft it turns with, speed ratio);
- ``inertias()``: (shaft, kg*m^2) pairs;
- ``varying_inertias(angle)``: (shaft, I, dI/dangle) triples for an inertia that
  varies with the angle of its shaft (``angle(shaft)``, rad), only with
  ``inertia_varies`` True; the element also gives the -1/2 I' w^2 torque that
  goes with it (the equation of motion of a varying inertia), and the core
  solves the bodies' response at each use instead of once per pass;
- ``torques(x)``: (shaft, N*m) pairs, positive in the shaft's positive sense;
- ``states()`` / ``rates(x)``: named states with initial values, and their rates;
- ``angles()``: shafts whose angle the element reads (``x.angle(shaft)``, rad, 0 at
  the start): the core keeps one state and one output column ``<shaft>_angle``
  for each shaft some element asks for, and none otherwise;
- ``ledger(x)``: energy terms by name (J), each declared in ``ledger_kinds`` as
  "work" (done on the machine), "loss" (dissipated) or "potential" (stored),
  or "heat of <loss>" (where a loss went: its terms sum to that loss, a ledger
  of their own); kinetic energy is the core's;
- ``tables()``: piecewise-linear tables of time, name -> (times field, values field);
  their knots are segment boundaries and ``x.table(name)`` reads them;
- ``boundaries()`` and ``boundary_events(t)``: scheduled times and the events
  recorded at them (kinds listed in ``event_kinds``);
- ``observations(x)``: guards whose zero is recorded as an output row (kinds in
  ``observation_kinds``), positive before it; those named in ``crossings`` are
  recorded where they change sign either way (a value whose sign switches the
  element's law, found exactly instead of stepped across); those named in
  ``limits`` are thresholds crossed (a temperature limit): recorded even where
  another guard is located at the same instant, and located as tightly as a
  switch; ``observes(kind)`` False leaves a kind unwatched in this element as
  built (an optional limit not given: no guard at all); a crossing named in
  ``crossing_events`` (kind -> (event rising through zero, event falling)) is
  no row but an event named by the way it crossed (a rope going taut or slack);
- ``kinks(x)``: knot coordinates (named by ``kink_names()``), continuous in the
  state and whole numbers exactly where the element's torque has a kink (a
  table's knot in angle): the integration stops at the next whole number either
  way and restarts there, as at a scheduled boundary in time, so no step
  straddles a knot;
- ``cycles``: kinks that mark the end of a cycle of the machine (kink name ->
  event kind): each crossing is recorded as a row of that kind, and the budgets
  of switches, observations and kinks start again, so a machine that switches a
  few times every cycle (periodic stick-slip) runs for as many cycles as it
  likes while one that switches without end inside a cycle is chattering;
  ``cycle_angle()`` says how far (rad) its shafts turn in a cycle, for sizing the loop;
- ``extremes(x)``: running reductions for the summary, name -> (reduction, value)
  with reduction one of "max", "min", "first" (the first time the value is true),
  "first_value" (value a pair (condition, v): v where the condition first holds),
  "duration" (time spent while it is true; constant between switches);
- ``summary(x)``: values of the final state for the summary; every name of
  ``extremes`` and ``summary`` is declared in ``summaries`` with its units
  ("bool" for a yes/no);
- ``outputs(x)``: time series, described in ``columns`` (name -> (units, description));
  a column in units "1" is a flag or a mode, stored as a small integer;
- ``speed_scale()``: a speed (rad/s) typical of the element, for the slip resolution.

What the figures draw of a part is not the element's: :mod:`hoistsim.display` holds it as plain data,
so that reading and drawing a results file needs no machine.
"""

from __future__ import annotations

from typing import ClassVar

from ..._pytree import pytree_dataclass

# Modes of a coupling.  Integers, so that they can be traced and stored.
STUCK, SLIP_FORWARD, SLIP_BACKWARD, OPEN = 0, 1, 2, 3
MODE_NAMES = {STUCK: "locked", SLIP_FORWARD: "slipping+", SLIP_BACKWARD: "slipping-", OPEN: "open"}

# A coupling exactly at its static limit holds (|T| <= T_s).  Computed in floating
# point, a torque that equals the capacity wanders by a few ulps either side of
# it, and a steady lift at the limit would break away on round-off.  The capacity
# is therefore taken 1e-12 larger (relative) for every sticking decision and
# breakaway guard; that moves a genuine breakaway by ~1e-12 of its torque ramp's
# time scale, far inside any solver tolerance.
STICK_TOLERANCE = 1e-12
# And an absolute 1e-9 N*m above it: a coupling stuck at a restart with no capacity and no torque (a pawl
# that nothing pushes yet, a mesh at rest that nothing presses) has a breakaway guard of exactly zero there,
# and a guard that starts at zero cannot fire however far the torque then grows past the capacity.
TORQUE_RESOLUTION = 1e-9

# A relative speed below this fraction of the machine's speed scale is no slip at
# all when modes are decided at a boundary (and at t = 0).  Without it a slip of
# 1e-312 rad/s, a subnormal number that XLA flushes to zero but numpy keeps,
# would decide between sticking and slipping.  4 eps: the round-off of a speed of
# the order of the scale.
SLIP_RESOLUTION = 4 * 2.220446049250313e-16


class AbstractElement:
    """A part of the machine, selected by its scenario section (see the module docstring)."""

    section: ClassVar[str]
    columns: ClassVar[dict[str, tuple[str, str]]] = {}
    event_kinds: ClassVar[tuple[str, ...]] = ()  # scheduled events
    observation_kinds: ClassVar[tuple[str, ...]] = ()  # guards recorded as rows
    crossings: ClassVar[tuple[str, ...]] = ()  # of those, the ones recorded where they change sign either way
    # of those, the ones that are events named by the way they cross: kind -> (rising event, falling event)
    crossing_events: ClassVar[dict[str, tuple[str, str]]] = {}
    limits: ClassVar[tuple[str, ...]] = ()  # of those, thresholds: never lost to a coinciding event
    # of those, thresholds that make the scenario wrong: kind -> (the key to blame, the message, with {time})
    errors: ClassVar[dict[str, tuple[str, str]]] = {}
    summaries: ClassVar[dict[str, str]] = {}  # summary name -> units
    ledger_kinds: ClassVar[dict[str, str]] = {}  # energy term -> "work", "loss", "potential" or "heat of <loss>"
    cycles: ClassVar[dict[str, str]] = {}  # kink -> event kind recorded where it is crossed
    inertia_varies: ClassVar[bool] = False  # brings varying_inertias

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        pytree_dataclass(cls)

    def bodies(self) -> dict:
        return {}

    def shafts(self) -> dict:
        return {}

    def inertias(self) -> tuple:
        return ()

    def varying_inertias(self, angle) -> tuple:
        return ()

    def torques(self, x) -> tuple:
        return ()

    def states(self) -> dict:
        return {}

    def rates(self, x) -> dict:
        return {}

    def angles(self) -> tuple:
        return ()

    def ledger(self, x) -> dict:
        return {}

    def tables(self) -> dict:
        return {}

    def boundaries(self) -> tuple:
        return ()

    def boundary_events(self, t) -> tuple:
        return ()

    def observations(self, x) -> dict:
        return {}

    def observes(self, kind: str) -> bool:
        return True

    def kink_names(self) -> tuple:
        return ()

    def kinks(self, x) -> dict:
        return {}

    def cycle_angle(self):
        return None

    def extremes(self, x) -> dict:
        return {}

    def summary(self, x) -> dict:
        return {}

    def outputs(self, x) -> dict:
        return {}

    def speed_scale(self):
        return None


class AbstractCoupling(AbstractElement):
    """A friction coupling between two shafts, or a shaft and the ground.

    Its modes (stuck, slipping either way, open), the guards that switch them
    and the momentum-keeping reset at a lock are the core's, written once for
    every coupling; a coupling supplies only its numbers:
    - ``joins()``: the shafts it ties, (a, b), b None for the ground; it
      transmits a torque from a to b, positive when a drives b;
    - ``capacity(x)``: the largest torque it carries stuck (N*m, inf for no limit);
      ``capacity_toward(x, sign)`` where that differs with the torque's direction;
    - ``sliding_torque(x)``: the torque it passes while slipping (N*m, >= 0);
    - ``is_open(segment)``: whether it carries nothing over a whole segment.
    ``can_slip`` False: it is stuck or open, never slipping (no slip guards).
    ``pressed_by``: a shaft whose torque presses this coupling's faces (the
    torque a mesh's teeth pass presses their flanks): the torque its body
    passes into it, ``x.torque_into(shaft)``.  The sliding torque then grows
    by ``sliding_per_load(x, side)`` times that torque's magnitude, ``side``
    +1 where it pushes the way the coupling slips, -1 the other way (the core
    solves for the two together).
    ``reports_switches`` False: its mode changes are not events of their own
    (its scheduled events say what happened); ``switch_names`` renames the
    core's kinds for it (a body on a support: unlock -> ``lift_off``).
    ``gap(x)``: for a contact (a body resting on a support), how far apart its
    sides are (m or rad, at or below zero where they touch); None for a
    coupling whose sides always touch.  A contact's sides meet where the gap
    closes, not where their speeds do (a body at the top of its flight is not
    caught in mid-air), with the momentum-keeping reset of a lock: a plastic
    impact, whose kinetic energy the core adds to the state ``impact_state``
    (a loss of the ledger).
    """

    can_slip: ClassVar[bool] = True
    reports_switches: ClassVar[bool] = True
    # Stuck together with others that already hold the same motion (two holds on one shaft), the torque is
    # statically indeterminate: the couplings take it in their order, those that yield after the rest.
    yields: ClassVar[bool] = False
    # its slip's peaks are rows (the peak slip speed of a friction coupling); False where the slip is a
    # shaft turning freely (a pawl clicking over, a mesh rolling): its peaks say nothing its speed does not
    observes_slip_peak: ClassVar[bool] = True
    pressed_by: ClassVar[str | None] = None
    switch_names: ClassVar[dict[str, str]] = {}  # the core's switch kind -> this coupling's event kind
    impact_state: ClassVar[str | None] = None  # a contact's state that takes the kinetic energy its impacts lose

    def joins(self) -> tuple:
        raise NotImplementedError

    def capacity(self, x):
        raise NotImplementedError

    def capacity_toward(self, x, sign):
        """The capacity against a torque that pushes side a forwards (``sign`` +1) or backwards (-1):
        ``capacity(x)`` both ways, unless the coupling holds one way only (a pawl)."""
        return self.capacity(x)

    def sliding_torque(self, x):
        raise NotImplementedError

    def sliding_per_load(self, x, side):
        return 0.0

    def is_open(self, segment):
        return False

    def gap(self, x):
        return None

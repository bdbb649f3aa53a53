"""What a part of the machine may bring to a run: the element and coupling interfaces.

An element is a frozen dataclass (a pytree) whose fields are its traced numbers, a new value never
recompiling; fields declared ``static()`` are structure (a shaft's name).  It must say how its scenario
section builds it (``from_spec``); everything else it may bring is a method of :class:`AbstractElement`,
empty by default, so an element the scene does not name has no body, state, term, guard or column.
Elements speak of *shafts*: a body (a speed of its own in the state) or a shaft turning with one, whose
inertia and torques reach the body by equal kinetic energy and power.  ``x`` is the machine at one
instant (:class:`hoistsim.machine.core.dynamics.Instant`); what it brings is read at trace time.  A class
is abstract (named ``Abstract…``) or concrete, and a concrete one that lacks an abstract method fails
where it is defined, not where a run first calls it.
What the figures draw of a part is not the element's: :mod:`hoistsim.display` holds it as plain data, so
that reading and drawing a results file needs no machine.
"""

from __future__ import annotations

import abc
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


def abstract_methods(cls: type) -> list[str]:
    """The abstract methods ``cls`` has no body for, its own or inherited (what a concrete class must define)."""
    return sorted(name for name in dir(cls) if getattr(getattr(cls, name, None), "__isabstractmethod__", False))


class AbstractElement:
    """A part of the machine, built from its scenario section by ``from_spec``; each method below is what it
    may bring, and brings nothing unless it says otherwise."""

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
    # energy term -> "work" (done on the machine), "loss" (dissipated), "potential" (stored) or "heat of <loss>"
    # (where a loss went: a ledger of its own, its terms summing to that loss); the kinetic energy is the core's
    ledger_kinds: ClassVar[dict[str, str]] = {}
    # kink -> event kind recorded where it is crossed: the end of a cycle of the machine, where the budgets of
    # switches, observations and kinks start again (a machine that switches a few times a cycle runs for as
    # many cycles as it likes; one that switches without end inside a cycle is chattering)
    cycles: ClassVar[dict[str, str]] = {}
    inertia_varies: ClassVar[bool] = False  # brings varying_inertias
    # the shafts it declares (``shafts``) are parts of the shafts they turn with (a point on a shaft's rim):
    # what acts on them is what that shaft takes (the torque passed into it, x.torque_into)
    shafts_are_parts: ClassVar[bool] = False

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        # abstract or concrete (equinox's rule): a concrete class that lacks a method fails here, as it is
        # defined, not in the middle of a run that first calls it
        missing = abstract_methods(cls)
        if missing and not cls.__name__.startswith("Abstract"):
            raise TypeError(f"{cls.__name__} lacks {', '.join(missing)}: an element (a class whose name does not "
                            "start with Abstract) must define every abstract method of the classes it derives from")
        pytree_dataclass(cls)

    @classmethod
    @abc.abstractmethod
    def from_spec(cls, spec) -> AbstractElement:
        """The element its section builds: ``spec`` the section (validated, SI), ``scenario`` the whole."""

    def bodies(self) -> dict:
        """New bodies: name -> initial speed (rad/s)."""
        return {}

    def shafts(self) -> dict:
        """New shafts turning with others: name -> (the shaft it turns with, its speed over that one's)."""
        return {}

    def inertias(self) -> tuple:
        """Inertias on shafts: (shaft, kg*m^2) pairs."""
        return ()

    def varying_inertias(self, angle) -> tuple:
        """(shaft, I in kg*m^2, dI/d angle in kg*m^2/rad) for an inertia varying with ``angle(shaft)`` (rad)."""
        # only with inertia_varies: the element gives the -1/2 I' w^2 torque that goes with it (the equation
        # of motion of a varying inertia), and the core solves the bodies' response at each use
        return ()

    def torques(self, x) -> tuple:
        """Torques on shafts: (shaft, N*m) pairs, positive in the shaft's positive sense."""
        return ()

    def states(self) -> dict:
        """States of its own: name -> initial value."""
        return {}

    def rates(self, x) -> dict:
        """The rates of its states: name -> d(state)/dt (the state's units per s)."""
        return {}

    def angle_starts(self) -> dict:
        """Shaft -> its angle at t = 0 (rad), for the shafts it is (default 0)."""
        return {}

    def angle_columns(self) -> dict:
        """Shaft -> (its angle's column name, units, description), for the shafts it is that call their angle
        otherwise than ``<shaft>_angle`` (rad): a mass on a line's position (m)."""
        return {}

    def angles(self) -> tuple:
        """Shafts whose angle it reads (``x.angle(shaft)``, rad from the start): a state and column each."""
        # one state and one output column <shaft>_angle for each shaft some element asks for, none otherwise
        return ()

    def ledger(self, x) -> dict:
        """Energy terms: name -> J so far, each declared in ``ledger_kinds``."""
        return {}

    def tables(self) -> dict:
        """Piecewise-linear tables of time, read by ``x.table(name)``: name -> (times field, values field)."""
        # their knots are segment boundaries
        return {}

    def boundaries(self) -> tuple:
        """Scheduled times (s): segment boundaries."""
        return ()

    def boundary_events(self, t) -> tuple:
        """The events at a boundary at ``t`` (s): (kind in ``event_kinds``, whether it happens at t) pairs."""
        return ()

    def observations(self, x) -> dict:
        """Guards, positive before the zero recorded as a row: kind in ``observation_kinds`` -> value."""
        # a kind in crossings is recorded where its sign changes either way (a value whose sign switches the
        # element's law, found exactly instead of stepped across), and one in crossing_events is no row but the
        # event named by the way it crossed (a rope going taut or slack); one in limits is a threshold crossed
        # (a temperature limit), recorded even where another guard is located at the same instant, and located
        # as tightly as a switch
        return {}

    def observes(self, kind: str) -> bool:
        """Whether a kind of ``observation_kinds`` is watched as built (an optional limit not given: no guard)."""
        return True

    def kink_names(self) -> tuple:
        """The names of what ``kinks`` counts."""
        return ()

    def kinks(self, x) -> dict:
        """Knots of its torque in the state: name -> a count, continuous and whole exactly at each knot."""
        # a table's knot in angle: the integration stops at the next whole number either way and restarts
        # there, as at a scheduled boundary in time, so no step straddles a knot
        return {}

    def cycle_angle(self):
        """How far its shafts turn in a cycle of ``cycles`` (rad), for sizing the loop; None: no cycle."""
        return None

    def extremes(self, x) -> dict:
        """Running reductions for the summary: name (in ``summaries``) -> (reduction, value)."""
        # reduction "max", "min", "first" (the first time the value is true), "first_value" (value a pair
        # (condition, v): v where the condition first holds) or "duration" (time spent while it is true;
        # constant between switches)
        return {}

    def summary(self, x) -> dict:
        """Values of the final state for the summary: name (in ``summaries``, "bool" a yes/no) -> value."""
        return {}

    def outputs(self, x) -> dict:
        """Output columns at this instant: name (in ``columns``: units, description) -> value."""
        # a column in units "1" is a flag or a mode, stored as a small integer
        return {}

    def speed_scale(self):
        """A speed typical of the element (rad/s), for the slip resolution; None: none."""
        return None

    def longest_step(self):
        """The longest step (s) its torques in time allow, None: any.  A machine held at rest has nothing else to
        bound its steps, and a step over a whole swing of a harmonic torque would hide its rise over what a hold
        carries and its fall back (the guards read at the steps' ends, the margins' valleys too)."""
        return None


class AbstractCoupling(AbstractElement):
    """A friction coupling between two shafts, or a shaft and the ground.

    Its modes (stuck, slipping either way, open), the guards that switch them and the momentum-keeping
    reset at a lock are the core's, written once for every coupling; a coupling supplies only its numbers.
    """

    can_slip: ClassVar[bool] = True  # False: stuck or open, never slipping (no slip guards)
    # False: its mode changes are no events of their own (its scheduled events say what happened)
    reports_switches: ClassVar[bool] = True
    # Stuck together with others that already hold the same motion (two holds on one shaft), the torque is
    # statically indeterminate: the couplings take it in their order, those that yield after the rest.
    yields: ClassVar[bool] = False
    # ... and one that takes the torque before every other (a stop, before the friction that also holds its mass)
    holds_first: ClassVar[bool] = False
    # its slip's peaks are rows (the peak slip speed of a friction coupling); False where the slip is a
    # shaft turning freely (a pawl clicking over, a mesh rolling): its peaks say nothing its speed does not
    observes_slip_peak: ClassVar[bool] = True
    # a shaft whose torque presses the faces (a mesh's teeth pass it into their flanks): the torque its body
    # passes into the coupling, x.torque_into(shaft), which the core solves for with the sliding torque
    pressed_by: ClassVar[str | None] = None
    switch_names: ClassVar[dict[str, str]] = {}  # the core's switch kind -> this coupling's event kind
    # Its capacity differs with the way it is pushed (a mesh's, whose losses depend on the side that drives):
    # its margin (capacity less |torque|) jumps where the torque changes sign, so a step from one side to the
    # other hides the valley between; each way's margin (capacity -+ torque, smooth) has a valley guard instead.
    margin_each_way: ClassVar[bool] = False
    # A contact (one with a gap) meets where the gap closes, not where the speeds do (a body at the top of
    # its flight is not caught in mid-air), with the reset of a lock: a plastic impact, whose kinetic energy
    # the core adds to this state (a loss of the ledger).
    impact_state: ClassVar[str | None] = None
    # A drive (a prescribed motion): stuck, it holds its sides' relative motion at ``motion(x)``, not at rest
    # (held between the shaft and the ground; the core solves for the torque that takes), and the impulses that
    # keep the speed it holds do work, which the core adds to its ``work_state``.
    drives: ClassVar[bool] = False

    @abc.abstractmethod
    def joins(self) -> tuple:
        """The shafts it ties, (a, b), b None for the ground; the torque it passes is positive a driving b.
        One that ties more than two shafts (a linear relation among their speeds) names them all."""

    def weights(self) -> tuple:
        """(shaft, weight) pairs: its relative speed is the sum of weight times speed, and it takes weight
        times its torque from each shaft.  Side a's weight 1 and side b's -1 unless it says otherwise (one
        that ties three shafts holds sum w_i speed_i = 0: its weights sum to zero, its torques balance)."""
        a, b = self.joins()
        return ((a, 1.0),) if b is None else ((a, 1.0), (b, -1.0))

    @abc.abstractmethod
    def capacity(self, x):
        """The largest torque it carries stuck (N*m; inf: no limit)."""

    def capacity_toward(self, x, sign):
        """The capacity against a torque that pushes side a forwards (``sign`` +1) or backwards (-1):
        ``capacity(x)`` both ways, unless the coupling holds one way only (a pawl)."""
        return self.capacity(x)

    @abc.abstractmethod
    def sliding_torque(self, x):
        """The torque it passes while slipping (N*m, >= 0)."""

    def sliding_per_load(self, x, side):
        """The sliding torque's growth per N*m of ``pressed_by``'s torque, ``side`` +1 pushing the way it slips."""
        return 0.0

    def pressed_beside(self, x):
        """A torque that presses the faces besides ``pressed_by``'s, pushing the way it slips (N*m where that
        torque is read: a friction beyond the faces, which they carry too, as a mesh's teeth carry the output
        bearings' friction), or None: none (no term traced)."""
        return None

    def is_open(self, segment):
        """Whether it carries nothing over a whole segment."""
        return False

    def motion(self, x) -> tuple:
        """A drive's (relative speed or None, relative acceleration) it holds its sides at: rad/s, rad/s^2 (None:
        the speed they have, where it prescribes the acceleration alone)."""
        return (0.0, 0.0)

    @property
    def work_state(self) -> str | None:
        """A drive's state of the work it has done (J), where the core adds its impulses' work."""
        return None

    def gap(self, x):
        """For a contact, how far apart its sides are (m or rad, <= 0 touching); None: its sides always touch."""
        return None

    def restitution(self, x) -> tuple | None:
        """For a contact whose sides rebound where they meet: (e, the slowest rebound): they part again at e times
        the relative speed they met at, or stay together where that would be slower (rad/s or m/s).  None: they
        meet in a plastic impact and stay together."""
        return None


"""Switching couplings, written once: guards, the static check and mode transitions.

Every coupling that can slip brings the same guards, positive inside their mode
and an event where they fall to zero (a constant 1 outside it, so they never
fire there); a crossing needs a strictly positive value before a non-positive one,
so a guard that is exactly zero at a restart cannot fire.
- ``slip``: the relative speed in the direction of slip, plus a negligible slip,
  reaches 0 when the two sides meet.  After an unlock or a reversal the slip
  restarts at exactly zero; were the guard zero there too, an excursion that
  returns within the first step would go unseen, so it is offset by the slip
  resolution (~3e-14 rad/s at 300 rpm) and starts positive.  It cannot fire at
  once: the stick tolerance makes the slip grow the right way from a restart.
- ``breakaway+`` / ``breakaway-``: the capacity less / plus the torque a stuck
  coupling carries: 0 when side a breaks away forwards / backwards.
- ``slip_peak`` (an observation): the rate of |slip| while not stuck, through 0
  where the slip speed peaks, so the peak is a row, not a sample.
- For a contact (a coupling with a ``gap``: a body resting on a support) the
  sides meet where the gap closes instead, and its valley is where they stop
  closing (the relative speed rising through 0).
- ``slip_valley`` (a safeguard): minus the rate of the slip in its direction,
  through 0 where the slip stops shrinking.  With a loose tolerance one step can
  carry the slip below zero and back so that neither end of the step shows the
  crossing; the valley between is always seen, and if the slip there has the
  wrong sign the loop re-solves with shorter steps.
- ``margin_valley`` (a safeguard, the same for a stuck coupling): minus the rate
  of its margin (capacity less |torque|), through 0 where the margin stops
  shrinking.  A machine held
  at rest has nothing for the step size to resolve, so a torque in time may
  rise over the capacity and fall back within one step; the margin's valley is
  always seen, and if the coupling is over its capacity there the loop
  re-solves with shorter steps.  A coupling whose capacity differs with the way
  it is pushed (``margin_each_way``: a mesh whose losses depend on the side that
  drives) has a margin that jumps where its torque changes sign, and a step
  across such a jump reads the margin falling at both ends, the valley between
  unseen (a held mesh missed its start forwards so in a Modelica example): each way's
  margin (capacity less / plus the torque, smooth) has its valley guard instead
  (``margin_valley+``, ``margin_valley-``).

Switching guards come first: a pass ends at the earliest crossing of a step, and
where two guards reach zero at one instant the first in this order fired: a
switch is never skipped for an observation (and one that crossed and came back
within the step is found by a pass solved again with the switches held off: see
``held_off``).  Limits come next, before the
other observations: a threshold's instant is an answer of its own.

Observations and valleys restart at their own zero, where round-off alone
decides the sign of a rate that is passing through zero: a restart state a few
ulps different from the root's could read slightly positive and fire again at
once, without end (seen in a vmapped sweep whose slip settles into a steady
value).  So a guard that ended the previous pass is lowered, for the next pass,
by its own (non-negative, round-off sized) value at the restart: it starts at
or below zero and cannot fire before it has genuinely risen again (``offsets``).
"""

from __future__ import annotations

import functools
from functools import cached_property

import jax
import jax.numpy as jnp

from . import guard_roles
from .dynamics import Instant, rates_at, slip_sign, vector_field
from .element import OPEN, SLIP_BACKWARD, SLIP_FORWARD, SLIP_RESOLUTION, STICK_TOLERANCE, STUCK, TORQUE_RESOLUTION
from .guard_id import (BREAKAWAY_BACKWARD, BREAKAWAY_FORWARD, MARGIN_VALLEY, MARGIN_VALLEYS_EACH_WAY, SLIP, SLIP_PEAK,
                       SLIP_VALLEY, GuardId, knot_guards)
from .layout import DISENGAGE, ENGAGE, LOCK, NO_EVENT, REVERSAL, UNLOCK, Layout

# A pass that starts within this of a knot (in knots) starts at it: the next ones are a whole knot away.
KNOT_RESOLUTION = 1e-9


def holding_capacity(coupling, x, sign):
    """The capacity with the stick tolerance: what a stuck coupling is allowed to carry against a torque
    pushing side a forwards (``sign`` > 0) or backwards."""
    return coupling.capacity_toward(x, sign) * (1.0 + STICK_TOLERANCE) + TORQUE_RESOLUTION


class GuardInstant:
    """(t, y) where a pass reads its guards, all of them at once: the machine there, and the couplings'
    margin rates, each worked out once for every guard that reads it (a smaller traced program and
    compile time than one a guard)."""

    def __init__(self, t, y, args):
        self.t, self.y, self.args = t, y, args

    @cached_property
    def instant(self) -> Instant:
        args = self.args
        return Instant(args.layout, self.t, self.y, args.modes, args.segment.table, args.reply)

    @cached_property
    def _margins_rates(self):
        """d/dt of each coupling's margin were it stuck (capacity less |torque|), then of each way's margin
        (capacity less / plus the torque) of every coupling whose capacity differs with the way it is pushed,
        along the motion at (t, y): one ``jvp`` for both (one copy of the machine's tangent in the program)."""
        args, layout = self.args, self.args.layout
        couplings = layout.coupling_elements
        each = [k for k, c in enumerate(couplings) if c.margin_each_way]

        def margins(t, y):
            x = Instant(layout, t, y, args.modes, args.segment.table, args.reply)
            torques = [jnp.asarray(x.coupling_torque(c.section), dtype=jnp.float64) for c in couplings]
            out = [holding_capacity(c, x, jnp.sign(q)) - jnp.abs(q) for c, q in zip(couplings, torques)]
            for k in each:
                out += [holding_capacity(couplings[k], x, 1.0) - torques[k],
                        holding_capacity(couplings[k], x, -1.0) + torques[k]]
            return jnp.stack(out)

        at = jnp.asarray(self.t, dtype=jnp.float64)
        _, rates = jax.jvp(margins, (at, self.y), (jnp.ones_like(at), rates_at(self.instant, self.y.dtype)))
        rates = jnp.where(jnp.isfinite(rates), rates, -1.0)  # a coupling that holds whatever it carries: no valley
        n = len(couplings)
        return rates[:n], {k: (rates[n + 2 * i], rates[n + 2 * i + 1]) for i, k in enumerate(each)}

    @property
    def margin_rates(self):
        """d/dt of each coupling's margin were it stuck (capacity less |torque|) along the motion at (t, y):
        the margins' derivative in the direction (1, dy/dt)."""
        return self._margins_rates[0]

    @property
    def margin_rates_each_way(self) -> dict:
        """d/dt of each way's margin (capacity less / plus the torque) of every coupling whose capacity
        differs with the way it is pushed (``margin_each_way``), by coupling index: (forwards, backwards)."""
        return self._margins_rates[1]


def touching(coupling, x):
    """Whether a coupling's sides touch: always, but for a contact whose gap is open."""
    gap = coupling.gap(x)
    return jnp.ones((), bool) if gap is None else gap <= 0.0


def guards(layout: Layout) -> list[tuple[str, GuardId, object]]:
    """(role, identity, guard function of a :class:`GuardInstant`) of every guard, in order: at one instant
    the first listed fires.

    Roles: "switch" (a mode change), "observe" (a row is recorded), "limit" (a row, never lost to a
    coinciding event), "valley", "kink" (a restart).
    Identities: a coupling's section and the guard's kind, an element's section and its observation's, or
    its knot coordinate's and the side (:mod:`.guard_id`).
    """
    switch, limit, observe, valley = [], [], [], []
    for k, coupling in enumerate(layout.coupling_elements):
        if not coupling.can_slip:
            continue
        name = coupling.section
        peak_id, dip_id, margin_id = (GuardId(name, kind) for kind in (SLIP_PEAK, SLIP_VALLEY, MARGIN_VALLEY))

        def slip(at, k=k, name=name, coupling=coupling):
            x, args = at.instant, at.args
            s = slip_sign(args.modes[k])
            gap = coupling.gap(x)
            if gap is not None:  # a contact: its sides meet where the gap closes
                return jnp.where(s != 0.0, gap, 1.0)
            return jnp.where(s != 0.0, s * x.relative_speed(name) + SLIP_RESOLUTION * args.speed_scale, 1.0)

        def breakaway(sign, k=k, coupling=coupling, name=name):
            def guard(at):
                x = at.instant
                return jnp.where(at.args.modes[k] == STUCK,
                                 holding_capacity(coupling, x, sign) - sign * x.coupling_torque(name), 1.0)
            return guard

        def peak(at, k=k, name=name, peak_id=peak_id):
            x, args = at.instant, at.args
            growth = jnp.sign(x.relative_speed(name)) * x.relative_acceleration(name)
            return jnp.where((args.modes[k] != STUCK) & args.observing, growth - args.offsets[peak_id], 1.0)

        def dip(at, k=k, name=name, coupling=coupling, dip_id=dip_id):
            x, args = at.instant, at.args
            s = slip_sign(args.modes[k])
            # where the slip stops shrinking; for a contact, where its sides stop closing (the gap's low point)
            closing = (-x.relative_speed(name) if coupling.gap(x) is not None
                       else -s * x.relative_acceleration(name))
            return jnp.where((s != 0.0) & args.observing, closing - args.offsets[dip_id], 1.0)

        def margin_dip(at, k=k, margin_id=margin_id, way=None):
            falling = -(at.margin_rates[k] if way is None else at.margin_rates_each_way[k][way])
            return jnp.where((at.args.modes[k] == STUCK) & at.args.observing,
                             falling - at.args.offsets[margin_id], 1.0)

        switch += [("switch", GuardId(name, SLIP), held_off(slip)),
                   ("switch", GuardId(name, BREAKAWAY_FORWARD), held_off(breakaway(1.0))),
                   ("switch", GuardId(name, BREAKAWAY_BACKWARD), held_off(breakaway(-1.0)))]
        if coupling.observes_slip_peak:
            observe.append(("observe", peak_id, peak))
        valley.append(("valley", dip_id, dip))
        if coupling.margin_each_way:
            valley += [("valley", GuardId(name, kind), functools.partial(margin_dip, margin_id=GuardId(name, kind),
                                                                          way=way))
                       for way, kind in enumerate(MARGIN_VALLEYS_EACH_WAY)]
        else:
            valley.append(("valley", margin_id, margin_dip))
    for element in layout.elements:
        for kind in (k for k in element.observation_kinds if element.observes(k)):
            guard_id = GuardId(element.section, kind)

            def seen(at, element=element, kind=kind, guard_id=guard_id):
                args = at.args
                value = element.observations(at.instant)[kind] * args.orients.get(guard_id, 1.0)
                return jnp.where(args.observing, value - args.offsets[guard_id], 1.0)
            role = "limit" if kind in element.limits else "observe"
            (limit if role == "limit" else observe).append((role, guard_id, seen))
    kinks = []
    for element in layout.elements:
        for kink in element.kink_names():
            # The knots either side of where the pass started (``args.anchors``: the knot coordinate there and
            # its rate): the distance to each falls monotonically to zero, so none is stepped over.  A pass that
            # starts on a knot watches the next knot the way it moves and that same knot behind it (a speed
            # that reaches a knot and turns back through it before anything else stops the pass), a hair past
            # it (two knot resolutions) so that the guard starts above zero, armed, and off the knot.
            anchor = GuardId(element.section, kink)

            def ahead(at, element=element, kink=kink, anchor=anchor):
                u = element.kinks(at.instant)[kink]
                start, rate = at.args.anchors[anchor]
                knot = jnp.floor(start + KNOT_RESOLUTION)
                target = jnp.where(on_knot(start) & (rate < 0.0), knot + 2.0 * KNOT_RESOLUTION, knot + 1.0)
                return jnp.where(at.args.kinking, target - u, 1.0)

            def behind(at, element=element, kink=kink, anchor=anchor):
                u = element.kinks(at.instant)[kink]
                start, rate = at.args.anchors[anchor]
                knot = jnp.ceil(start - KNOT_RESOLUTION)
                target = jnp.where(on_knot(start) & (rate > 0.0), knot - 2.0 * KNOT_RESOLUTION, knot - 1.0)
                return jnp.where(at.args.kinking, u - target, 1.0)
            to_ahead, to_behind = knot_guards(element.section, kink)
            kinks += [("kink", to_ahead, ahead), ("kink", to_behind, behind)]
    every = switch + limit + observe + valley + kinks
    # a machine with nothing to watch (a free rotor) still has a guard: one that never falls, so a pass
    # runs to its segment's end as any other
    return every or [("valley", GuardId(layout.sections[0], "nothing"), lambda at: jnp.ones(()))]


@jax.jit
def guard_values(t, y, args):
    """Every guard at (t, y), in the order of :func:`guards`: one array.

    A pass reads its guards where it starts, at each step's end, in the
    crossing's search and where it stops; traced once as a call of its own (a jitted
    function), the program is traced and lowered with one copy of them
    instead of one a place.
    """
    at = GuardInstant(t, y, args)
    return jnp.stack([jnp.asarray(g(at), dtype=jnp.float64) for _, _, g in guards(args.layout)])


def held_off(guard):
    """A switch guard that stays positive up to ``args.switches_from``: a pass solved again, up to that
    instant, to find a limit or an observation that crossed and came back within the step (loop._step)."""
    def held(at):
        value = guard(at)
        return value if at.args.switches_from is None else jnp.where(at.t <= at.args.switches_from, 1.0, value)
    return held


def orients(layout: Layout, t, y, args) -> dict:
    """The way each two-way observation (an element's ``crossings``) leaves (t, y): +1 rising, -1 falling.

    Its guard is the value times this, positive as the pass goes on, so that it
    fires where the value next changes sign, either way.  At its own zero (a
    pass that starts where the last one found it) the value's rate says which
    way it goes.
    """
    out = {}
    for element in layout.elements:
        for kind in (k for k in element.crossings if element.observes(k)):
            def value(t, y, element=element, kind=kind):
                return element.observations(Instant(layout, t, y, args.modes, args.segment.table, args.reply))[kind]

            rate_y = vector_field(t, y, args)
            now, rate = jax.jvp(value, (jnp.asarray(t, y.dtype), y), (jnp.ones((), y.dtype), rate_y))
            out[GuardId(element.section, kind)] = jnp.where(now != 0.0, jnp.sign(now), jnp.where(rate < 0.0, -1.0, 1.0))
    return out


def crossed_together(guards, values, starting, located, events=frozenset(), passed_over=None):
    """Which guards crossed zero in the same step as the one located at (t, y).

    A pass ends at the earliest crossing of the guards that changed sign over a
    step; another guard (not a switch) already past its zero at the located root
    crossed and came back within the step (the step's ends did not show it): it
    was *overtaken*, and the pass must be solved again.  One only just past zero crossed with the located
    one, as far as a row can tell: a knot coordinate by less than the knot
    resolution; an observation by less than 1e-4 of its value where the pass
    started (``starting``), a root so close that the row already there misses its
    extreme by ~1e-8; a limit by less than 1e-9 of it (a threshold's instant is
    an answer, not a row beside one).  Returns (an observation overtaken, a
    limit overtaken, and on the guard vector (those :func:`.guard_roles.reported`) the knots reached and the
    limits and events crossed at (t, y) along with the located guard: a period that ends on a table's knot is
    reached; a limit reached as a coupling locks was crossed, there; a backlash's sides parting where the shaft
    they let go of turns round was an event, there; a coupling's slip zero reached with the located one (a shaft
    stopping against two holds at once), to be decided with it). ``values``, ``starting``: every guard at (t, y)
    and where the pass started (:func:`guard_values`); ``located``: the guard the search located (a mask);
    ``events``: the observations that are events (their elements' ``crossing_events``); ``passed_over``: the knots
    the pass steps over (:func:`.guard_roles.passed_over`), neither overtaken nor reached: one the located guard's
    step went past is behind it, as the step allowed.  Array operations over the
    guard vector, the roles constant masks: a few operations whatever the number of guards.
    """
    switch, kink, limit = (guard_roles.of_role(guards, role) for role in ("switch", "kink", "limit"))
    armed = starting > 0.0
    if passed_over is not None:
        armed = armed & ~passed_over
    beside = armed & ~located  # armed where the pass started, and not the guard located
    resolution = jnp.where(kink, KNOT_RESOLUTION, jnp.where(limit, 1e-9, 1e-4) * jnp.abs(starting))
    passed = ~switch & beside & (values < -resolution)
    overtaken = jnp.any(passed & ~limit)
    limit_overtaken = jnp.any(passed & limit)
    # a knot reached within its resolution; a limit, an event or a slip zero (the search stopped at the first
    # root in list order: this one shares it) at or below zero
    reached = jnp.where(kink, armed & (values <= KNOT_RESOLUTION), beside & (values <= 0.0))
    return overtaken, limit_overtaken, reached & guard_roles.reported(guards, events)


def on_knot(start):
    """Whether a knot coordinate where a pass starts is on a knot (within the knot resolution of one)."""
    return jnp.abs(start - jnp.round(start)) <= KNOT_RESOLUTION


def kink_anchors(layout: Layout, instant_at, t, y) -> dict:
    """Every knot coordinate at the start of a pass and its rate along the motion there (see ``guards``):
    ``instant_at(t, y)`` the machine at (t, y) under the pass's modes."""
    kinked = [e for e in layout.elements if e.kink_names()]
    if not kinked:
        return {}

    def coordinates(t, y):
        x = instant_at(t, y)
        return {GuardId(e.section, kink): jnp.asarray(value, dtype=jnp.float64) for e in kinked
                for kink, value in e.kinks(x).items()}

    at = jnp.asarray(t, dtype=jnp.float64)
    values, rates = jax.jvp(coordinates, (at, y), (jnp.ones_like(at), rates_at(instant_at(t, y), y.dtype)))
    return {name: (values[name], rates[name]) for name in values}


def transition_kind(previous, new):
    """Event kind recorded when a coupling's mode changes (NO_EVENT if it does not)."""
    slipping_before = (previous == SLIP_FORWARD) | (previous == SLIP_BACKWARD)
    kind = jnp.where(new == STUCK, LOCK,
           jnp.where(new == OPEN, DISENGAGE,
           jnp.where(previous == STUCK, UNLOCK,
           jnp.where(previous == OPEN, ENGAGE, REVERSAL))))
    changed = (previous != new) & ((previous == STUCK) | (previous == OPEN) | slipping_before)
    return jnp.where(changed, kind, NO_EVENT)

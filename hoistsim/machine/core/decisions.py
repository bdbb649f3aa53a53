"""What a switch or a boundary does to the couplings: the static check decides them, the events are recorded.

The loop (:mod:`.loop`) calls :func:`apply_event` where a pass ends at a guard (an observation's row, or a
switch left pending) and :func:`decide` where the next pass starts (at a boundary, or after a switch):
one static check a step in the compiled program.
"""

from __future__ import annotations

import functools

import equinox as eqx
import jax.numpy as jnp

from . import impacts, static_check, switching
from .bodies import keep_momentum
from .dynamics import Instant, slip_sign
from .element import SLIP_BACKWARD, SLIP_FORWARD, SLIP_RESOLUTION, STUCK
from .eventlog import record
from .guard_id import BREAKAWAY_BACKWARD, BREAKAWAY_FORWARD, SLIP, GuardId, knot_guards
from .layout import NO_EVENT, SWITCH_KINDS

# Where one coupling's sides meet, another's meet at the same instant if their relative speed is within
# this many slip resolutions (the round-off of the located root).
SHARED_ZERO = 16


def _record_transitions(plan, segment, c, when, t, y, before, after,
                        columns: bool):
    """One event row per coupling whose mode changed (if it reports its switches); count them."""
    layout = plan.layout
    margins = static_check.margins(layout, segment, t, y, after) if columns else None
    for k, (index, coupling) in enumerate(zip(layout.couplings, layout.coupling_elements)):
        if not coupling.reports_switches:
            continue
        kind = switching.transition_kind(before[k], after[k])
        happened = when & (kind != NO_EVENT)
        if coupling.switch_names:  # the coupling's own names for them (lifting off a support)
            codes = jnp.asarray([layout.switch_code(coupling, core) for core in range(len(SWITCH_KINDS))])
            kind = jnp.where(happened, codes[jnp.maximum(kind, 0)], kind)
        c = record(c, happened, t, kind, index, y, after, margins[k] if columns else jnp.nan)
        c = eqx.tree_at(lambda q: q.switches, c, c.switches + happened)
    return c


def _driven(layout, segment, y, held):
    """The speeds where a boundary starts, the drives at theirs: a speed that a drive's signal steps (or an angle's
    kink) jumps, carried by the couplings that never slip and nothing else (a friction coupling carries no
    impulse: its sides part, and the static check then finds it slipping)."""
    rigid = [jnp.asarray(not e.can_slip) & ~jnp.asarray(e.is_open(segment)) for e in layout.coupling_elements]
    return keep_momentum(layout, y, rigid, held)


def decide(plan, segment, c, columns: bool):
    """At a boundary, or after a switch located where the last pass ended: the static check decides the
    couplings (one copy of it in the program for both), the scheduled events and the switches are recorded.

    At a boundary every coupling whose sides move together is a candidate (the scheduled change may free or
    catch any); after a switch, those the guards that fired leave stuck or meeting.
    """
    layout = plan.layout
    at = c.at_boundary
    held = Instant(layout, c.t, c.y, table=segment.table).held_speeds()
    y = c.y if held is None else jnp.where(at, _driven(layout, segment, c.y, held), c.y)
    boundary_modes, boundary_candidates = static_check.candidates_at_boundary(layout, segment, y, plan.speed_scale)
    modes = jnp.where(at, boundary_modes, c.pending_modes).astype(c.modes.dtype)
    candidates = [jnp.where(at, b, c.pending_candidates[k]) for k, b in enumerate(boundary_candidates)]
    when = at | c.pending
    c, y, modes, candidates, plastic = impacts.meet(plan, c, y, modes, candidates, held, when)
    decided, met = static_check.settle(layout, segment, c.t, y, modes, candidates, held)
    # at a boundary the stuck ones' sides take their common speed; after a switch the candidates' met already
    met = jnp.where(at, keep_momentum(layout, y, [m == STUCK for m in decided], held), met)
    decided_y = impacts.with_losses(layout, y, met, plastic)
    before = c.modes
    new_modes = jnp.where(when, decided, c.modes)
    c = eqx.tree_at(lambda k: (k.y, k.modes, k.pending), c,
                    (jnp.where(when, decided_y, c.y), new_modes, jnp.zeros((), bool)))
    for index, element in enumerate(layout.elements):
        for kind, happens in element.boundary_events(c.t):
            c = record(c, at & happens, c.t, layout.kind_code(kind), index, c.y, new_modes, jnp.nan)
    c = impacts.record_impacts(plan, c, plastic, new_modes)
    # The first decision (t = 0) sets the initial modes; it is not an event.
    before = jnp.where(c.segments == 0, -1, before)
    return _record_transitions(plan, segment, c, when, c.t, c.y, before, new_modes, columns)


def apply_event(plan, segment, c, t, y, masks: dict, hit, coinciding: dict,
                 orients: dict):
    """A guard fired at (t, y): an observation's row, or a switch (lock, reverse or unlock) left pending
    for the static check where the next pass starts.

    ``coinciding``: knots reached at (t, y) along with the guard that fired; ``orients``: the way each
    two-way observation left the pass's start (+1: it fell to zero; see switching.orients).
    """
    layout = plan.layout
    # At most one guard fires at a time (the earliest; the first listed at one instant): one row for any observation.
    observed, kind, element = jnp.zeros((), bool), NO_EVENT, -1
    codes = {}
    for role, name, _ in switching.guards(layout):
        if role in ("observe", "limit"):
            named = layout.elements[layout.sections.index(name.section)].crossing_events.get(name.kind)
            codes[name] = layout.kind_code(name.kind) if named is None else jnp.where(
                orients[name] > 0, layout.kind_code(named[1]), layout.kind_code(named[0]))
            kind = jnp.where(masks[name], codes[name], kind)
            element = jnp.where(masks[name], layout.sections.index(name.section), element)
            observed = observed | masks[name]
    c = record(c, observed, t, kind, element, y, c.modes, jnp.nan)
    # A limit or an event crossed at the same instant as the located guard: a row of its own, at that instant.
    for name, crossed in coinciding.items():
        if name in codes:
            c = record(c, crossed, t, codes[name], layout.sections.index(name.section), y, c.modes, jnp.nan)
            c = eqx.tree_at(lambda k: k.observations, c, c.observations + crossed)
    valley = functools.reduce(jnp.logical_or, [masks[n] for r, n, _ in switching.guards(layout) if r == "valley"],
                              jnp.zeros((), bool))
    kinked = functools.reduce(jnp.logical_or, [masks[n] for r, n, _ in switching.guards(layout) if r == "kink"],
                              jnp.zeros((), bool))
    # A cycle's end: a row of its kind, and the budgets start again.
    cycled = jnp.zeros((), bool)
    for index, kink, kind in layout.cycles:
        names = knot_guards(layout.sections[index], kink)
        crossed = functools.reduce(jnp.logical_or, [masks[n] | coinciding[n] for n in names])
        c = record(c, crossed, t, layout.kind_code(kind), index, y, c.modes, jnp.nan)
        cycled = cycled | crossed
    c = eqx.tree_at(lambda k: (k.observations, k.kinks), c,
                    (c.observations + (observed | valley), c.kinks + kinked))
    now = jnp.stack([c.switches, c.observations, c.kinks])
    c = eqx.tree_at(lambda k: k.cycle_start, c, jnp.where(cycled, now, c.cycle_start))
    hit = hit & ~observed & ~valley & ~kinked
    # Sides that meet move on together (momentum kept); a coupling whose
    # capacity is exceeded slips the way its torque pushes.
    modes, candidates = c.modes, [m == STUCK for m in c.modes]
    for k, coupling in enumerate(layout.coupling_elements):
        if not coupling.can_slip:
            continue
        name = coupling.section
        met, up, down = (masks[GuardId(name, kind)] for kind in (SLIP, BREAKAWAY_FORWARD, BREAKAWAY_BACKWARD))
        modes = modes.at[k].set(jnp.where(up, SLIP_FORWARD, jnp.where(down, SLIP_BACKWARD,
                                                                       jnp.where(met, STUCK, modes[k]))))
        candidates[k] = (candidates[k] & ~up & ~down) | met
    # Sides that meet where another coupling's sides meet (one zero of speed shared by both, a shaft
    # stopping against two holds at once) are tried stuck too: a pass reports one guard.  Shared: a slip
    # within round-off of zero, or a slip guard that crossed in the same step and is at or below zero at the
    # located root (the root's own resolution in time moves a slip by its acceleration times it, more than
    # round-off where the shaft decelerates fast).
    meeting = functools.reduce(jnp.logical_or, [masks[GuardId(e.section, SLIP)] for e in layout.coupling_elements
                                                if e.can_slip], jnp.zeros((), bool))
    x = Instant(layout, t, y)
    due = jnp.zeros((), bool)
    for k, coupling in enumerate(layout.coupling_elements):
        if not coupling.can_slip:
            continue
        shared = coinciding.get(GuardId(coupling.section, SLIP), jnp.zeros((), bool)) | (
            jnp.abs(x.relative_speed(coupling.section)) <= SHARED_ZERO * SLIP_RESOLUTION * plan.speed_scale)
        together = meeting & (slip_sign(modes[k]) != 0.0) & switching.touching(coupling, x) & shared
        # A slip already at or past its zero where a pass ended (its guard at or below zero, so that it could never
        # fire in the next): the pass ended at another guard's root within the search's resolution of the slip's
        # own, or a pass solved again with the switches held off reached the switch's instant.  Decided here.
        behind = (coupling.gap(x) is None) & (slip_sign(modes[k]) != 0.0) & (
            slip_sign(modes[k]) * x.relative_speed(coupling.section) + SLIP_RESOLUTION * plan.speed_scale <= 0.0)
        together = together | behind
        due = due | behind
        modes = modes.at[k].set(jnp.where(together, STUCK, modes[k]))
        candidates[k] = candidates[k] | together
        # A contact let go where its sides still touch (a mass pulled off its stop and held there by its friction)
        # has a gap guard that starts at or below zero and cannot fire: at every switch it is tried stuck again.
        gap = coupling.gap(x)
        if gap is not None:
            resting = hit & (modes[k] == SLIP_FORWARD) & (gap <= 0.0) & (
                x.relative_speed(coupling.section) <= SLIP_RESOLUTION * plan.speed_scale)
            modes = modes.at[k].set(jnp.where(resting, STUCK, modes[k]))
            candidates[k] = candidates[k] | resting
    # decided where the next pass starts, with the boundary's decision (one static check a step)
    return eqx.tree_at(lambda k: (k.pending, k.pending_modes, k.pending_candidates), c,
                       (hit | due, modes.astype(c.modes.dtype),
                        jnp.stack(candidates) if candidates else c.pending_candidates))

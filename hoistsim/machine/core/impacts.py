"""Contacts' impacts: where the sides of a contact meet, they stop together, or part again at once.

A contact's sides meet where its gap closes (a guard of :mod:`.switching`), and the static check locks them in a
plastic impact (momentum kept), whose kinetic energy taken is the contact's ``impact_state``, a loss of the ledger,
even where the static check then lets them part at once (a mass stopped by its stop and pulled off it).  A
contact with a restitution e (:meth:`.element.AbstractCoupling.restitution`) instead takes (1 + e) times the
plastic impact's impulse: Newton's law of impact, its sides parting at e times the speed they met at, the
couplings stuck before it kept stuck through it.  Where that rebound would
be slower than the contact's slowest, the impact is plastic after all and the sides rest together: a bounce that
would shrink without end (a ball coming to rest on the floor in infinitely many hops) ends in finitely many.
"""

from __future__ import annotations

import equinox as eqx
import jax.numpy as jnp

from .bodies import keep_momentum
from .dynamics import Instant, slip_sign
from .element import SLIP_FORWARD, SLIP_RESOLUTION, STUCK
from .eventlog import record
from .layout import LOCK
from .static_check import slip_mode


def meet(plan, c, y, modes, candidates, held, when):
    """Where a contact meets (a candidate to stick now, apart before): with a restitution and fast enough to
    rebound, the speeds after its impact, its kinetic energy taken added to its ``impact_state``, the contact let
    go (apart, slipping forwards).  Either way every other slipping coupling slips the way its sides part after
    the impact, or is a candidate to stick where they then move together (a mass's friction, which a stop stopped
    or turned round).  Where the couplings are decided now (``when``: a boundary, or a switch pending).  Returns
    (c with a rebound's event row, y, modes, candidates, each coupling's plastic impact: a contact that met and
    did not rebound, the kinetic energy that impact would take alone, and whether it arrived: closed at more than
    the slip resolution, not a contact at rest against it tried again at another's switch)."""
    layout = plan.layout
    couplings = layout.coupling_elements
    x = Instant(layout, c.t, y)
    plastic_impacts = [jnp.zeros((), bool)] * len(couplings)
    plastic_losses = [jnp.zeros(())] * len(couplings)
    arrivals = [jnp.zeros((), bool)] * len(couplings)
    tiny = SLIP_RESOLUTION * plan.speed_scale
    for k, coupling in enumerate(couplings):
        if coupling.gap(x) is None:
            continue
        meets = when & candidates[k] & (c.modes[k] != STUCK)
        arrivals[k] = meets & (-x.relative_speed(coupling.section) > tiny)
        # the impulse of the plastic impact, the couplings stuck through the pass kept stuck
        kept = [(c.modes[j] == STUCK) | (j == k) for j in range(len(couplings))]
        plastic = keep_momentum(layout, y, kept, held)
        plastic_losses[k] = x.kinetic_energy() - Instant(layout, c.t, plastic).kinetic_energy()
        law = coupling.restitution(x)
        if law is None:
            plastic_impacts[k] = meets
            modes, candidates = _slipping_as_they_part(plan, c.t, plastic, c.modes, modes, candidates, meets)
            continue
        e, slowest = law
        approach = -x.relative_speed(coupling.section)  # the contact's closing speed
        bounces = meets & (e * approach >= slowest)
        plastic_impacts[k] = meets & ~bounces
        bounced = y + (1.0 + e) * (plastic - y)  # Newton's: (1 + e) times the plastic impact's impulse
        lost = x.kinetic_energy() - Instant(layout, c.t, bounced).kinetic_energy()
        bounced = bounced.at[layout.state_index(coupling.impact_state)].add(lost)
        y = jnp.where(bounces, bounced, y)
        modes = modes.at[k].set(jnp.where(bounces, SLIP_FORWARD, modes[k]))
        candidates[k] = candidates[k] & ~bounces
        kind = layout.kind_code(coupling.switch_names.get("rebound", "rebound"))
        c = record(c, bounces, c.t, kind, layout.couplings[k], y, modes, jnp.nan)
        c = eqx.tree_at(lambda q: q.switches, c, c.switches + bounces)
        modes, candidates = _slipping_as_they_part(plan, c.t, jnp.where(bounces, y, plastic), c.modes, modes,
                                                   candidates, meets)
    return c, y, modes, candidates, (plastic_impacts, plastic_losses, arrivals)


def with_losses(layout, y_before, y_after, plastic):
    """``y_after`` with the kinetic energy the contacts' plastic impacts took (their sides met and moved on
    together, momentum kept; ``plastic`` from :func:`meet`) added to their ``impact_state``s.

    The whole loss is booked once, shared among the contacts that met at this instant in proportion to what each
    would take alone: a contact closing again at rest (a mass its friction held off its stop, touching it again)
    takes nothing of another's impact."""
    impacts, alone, _ = plastic
    contacts = [k for k, coupling in enumerate(layout.coupling_elements) if coupling.impact_state is not None]
    if not contacts:
        return y_after
    lost = Instant(layout, 0.0, y_before).kinetic_energy() - Instant(layout, 0.0, y_after).kinetic_energy()
    met = jnp.stack([impacts[k] for k in contacts])
    weights = jnp.where(met, jnp.maximum(jnp.stack([alone[k] for k in contacts]), 0.0), 0.0)
    total = jnp.sum(weights)
    # contacts that all met at rest took (next to) nothing alone: what was lost, shared evenly
    shares = jnp.where(total > 0.0, weights / jnp.where(total > 0.0, total, 1.0),
                       met / jnp.maximum(jnp.sum(met), 1))
    for share, k in zip(shares, contacts):
        y_after = y_after.at[layout.state_index(layout.coupling_elements[k].impact_state)].add(share * lost)
    return y_after


def record_impacts(plan, c, plastic, modes):
    """An event row for each plastic impact after which the static check let the contact's sides part at once (a
    lock and an unlock at one instant, which no change of its mode records): the contact's lock.  Only where the
    sides arrived: a contact resting against its stop, let go and held there by a friction, is tried stuck again at
    every other switch (its gap guard cannot fire), and parting again there is no impact."""
    layout = plan.layout
    x = Instant(layout, c.t, c.y)
    plastic_impacts, _, arrivals = plastic
    for k, coupling in enumerate(layout.coupling_elements):
        if coupling.gap(x) is None:
            continue
        parted = plastic_impacts[k] & arrivals[k] & (modes[k] != STUCK)
        c = record(c, parted, c.t, layout.switch_code(coupling, LOCK), layout.couplings[k], c.y, modes, jnp.nan)
        c = eqx.tree_at(lambda q: q.switches, c, c.switches + parted)
    return c


def _slipping_as_they_part(plan, t, y, before, modes, candidates, impact):
    """After a contact's impact (``impact``; ``y`` the speeds after it): each slipping coupling (not a contact)
    slips the way its sides now part, or is a candidate to stick where they move together.  One that breaks away
    at this instant (stuck ``before``) and whose sides the impact leaves together slips the way its guard said: its
    torque is past what it holds, and tried stuck again it would stay stuck by the stick tolerance alone, its
    breakaway guard then below zero, never to fire."""
    layout = plan.layout
    x = Instant(layout, t, y)
    tiny = SLIP_RESOLUTION * plan.speed_scale
    for j, coupling in enumerate(layout.coupling_elements):
        if not coupling.can_slip or coupling.gap(x) is not None:
            continue
        slip = x.relative_speed(coupling.section)
        slipping = impact & (slip_sign(modes[j]) != 0.0) & ~candidates[j]
        way = slip_mode(slip, tiny)
        breaking_away = (before[j] == STUCK) & (way == STUCK)
        modes = modes.at[j].set(jnp.where(slipping & ~breaking_away, way, modes[j]))
        candidates[j] = candidates[j] | (slipping & ~breaking_away & (way == STUCK))
    return modes, candidates

"""The static check: at a switch or a boundary, which couplings stay stuck and which slip, and which way.

A way of leaving the candidate couplings (each held, or let go forwards or backwards) is consistent
where every held coupling carries a torque within its capacity and every coupling let go could not
hold (its sides part its way even against its whole capacity) and slips the way its sides part.
:func:`settle` finds one; :func:`margins` says how far each coupling is from its capacity (the
event rows' torque margin).
"""

from __future__ import annotations

import functools
import itertools

import jax
import jax.numpy as jnp
import numpy as np

from .bodies import keep_momentum
from .dynamics import Instant, slip_sign
from .element import OPEN, SLIP_BACKWARD, SLIP_FORWARD, SLIP_RESOLUTION, STUCK
from .layout import Layout
from .switching import holding_capacity, touching


def slip_mode(slip, tiny):
    """The mode a relative speed says: slipping its way, or stuck (a candidate) within ``tiny`` of zero."""
    return jnp.where(slip > tiny, SLIP_FORWARD, jnp.where(slip < -tiny, SLIP_BACKWARD, STUCK))


def candidates_at_boundary(layout: Layout, segment, y, speed_scale):
    """Modes at a scheduled boundary before the static check, and which couplings may stick.

    Open over the segment: open.  Slipping by more than the slip resolution:
    slipping that way.  Otherwise (the sides move together): a candidate for
    sticking, decided by the static check.
    """
    x = Instant(layout, 0.0, y)
    tiny = SLIP_RESOLUTION * speed_scale
    modes, candidates = [], []
    for coupling in layout.coupling_elements:
        is_open = jnp.asarray(coupling.is_open(segment))
        if coupling.can_slip:
            slip = x.relative_speed(coupling.section)
            mode = slip_mode(slip, tiny)
            if coupling.gap(x) is not None:  # a contact's sides apart move freely (slip forwards) however fast
                mode = jnp.where(touching(coupling, x), jnp.where(slip > tiny, SLIP_FORWARD, STUCK), SLIP_FORWARD)
        else:
            mode = jnp.asarray(STUCK)
        mode = jnp.where(is_open, OPEN, mode)
        modes.append(mode)
        candidates.append(mode == STUCK)
    return jnp.stack(modes) if modes else jnp.zeros((0,), int), candidates


# The static check tries the ways a switch can leave its couplings (each held, or let go forwards or
# backwards): every way with up to this many couplings let go, the fewest first.
MOST_TRIED = 50_000


@functools.cache
def _ways(can_slip: tuple) -> np.ndarray:
    """Every way to leave the couplings, a row each: 0 held, 1 let go forwards, 2 let go backwards.

    Only couplings that can slip are let go.  Rows with fewer let go come first, so that the first
    consistent row holds as many couplings as can be held; within a count, the order is fixed.
    """
    free = [k for k, slips in enumerate(can_slip) if slips]
    rows = []
    for count in range(len(free) + 1):
        more = []
        for chosen in itertools.combinations(free, count):
            for directions in itertools.product((1, 2), repeat=count):
                row = [0] * len(can_slip)
                for k, d in zip(chosen, directions):
                    row[k] = d
                more.append(row)
        if len(rows) + len(more) > MOST_TRIED:
            break
        rows += more
    return np.asarray(rows, dtype=np.int8).reshape(len(rows), len(can_slip))


def _check(layout: Layout, segment, t, met, modes, candidate):
    """Each candidate's conditions in one way of leaving them (``modes``): (how far each held one is
    stressed, as a fraction of what it can hold; whether each one let go cannot hold; whether its sides
    part its way while it slides; the torque each carries).

    A held coupling must carry a torque within its capacity; one let go must be unable to hold (its
    sides part its way even against the whole of its capacity, or others hold them together) and
    slip the way its sides part while it slides.  One solve: the sides' parting against the
    capacity is the parting while sliding moved along the response to the coupling's own torque
    (linear; a coupling pressed by a shaft's torque, a mesh, holds what it slides with: no move).
    Where a coupling pressed by a shaft's torque (a mesh) can slip, its friction answers every other
    coupling's torque through the torque that presses it, so the parting against each one's capacity
    is solved again with it carrying that.
    """
    x = Instant(layout, t, met, modes, segment.table)
    reply = x.reply
    couplings = layout.coupling_elements
    signs = [slip_sign(modes[k]) for k in range(len(couplings))]
    partings = [signs[k] * x.relative_acceleration(c.section) for k, c in enumerate(couplings)]
    let_go = [candidate[k] & (signs[k] != 0.0) for k in range(len(couplings))]
    answered = any(c.can_slip and c.pressed_by is not None for c in couplings)
    stressed, cannot_hold, parting_ok, torques = [], [], [], []
    for k, coupling in enumerate(couplings):
        torque = jnp.asarray(x.coupling_torques[k], dtype=jnp.float64)
        held = candidate[k] & (modes[k] == STUCK)
        stressed.append(jnp.where(held, jnp.abs(torque) / holding_capacity(coupling, x, jnp.sign(torque)), 0.0))
        torques.append(torque)
        if not coupling.can_slip:
            cannot_hold.append(jnp.ones((), bool))
            parting_ok.append(jnp.ones((), bool))
            continue
        sign, parting = signs[k], partings[k]
        limit = holding_capacity(coupling, x, sign)
        cannot = parting >= 0.0
        if coupling.pressed_by is None:
            if answered:
                # A pressed coupling's friction answers this one's torque (what presses it grows with
                # that torque, and it slides with a share of it): the answer is no one column of the
                # response, so the machine is asked again with this coupling sliding with its capacity.
                sliding = [None] * len(couplings)
                sliding[k] = jnp.where(jnp.isfinite(limit), limit, coupling.sliding_torque(x))
                at_capacity = Instant(layout, t, met, modes, segment.table, reply=reply, sliding=sliding)

                def parting_then(j):
                    return signs[j] * at_capacity.relative_acceleration(couplings[j].section)
            else:
                # how each coupling's relative acceleration answers this one's signed sliding torque
                response = reply.accel_from_sliding[:, k]
                extra = jnp.where(jnp.isfinite(limit), limit, 0.0) - coupling.sliding_torque(x)

                def parting_then(j):  # its own parting moves with its own torque: no sign to apply
                    scale = extra if j == k else signs[j] * sign * extra
                    return partings[j] + scale * x.bodies.relative(j, response)
            # own answer negative: friction holds the sides
            cannot = parting_then(k) >= 0.0
            # Carrying its whole capacity, it would stop another let go from sliding the way it does (a
            # mesh's law, which changes with the way it rolls, met a torque its present way cannot
            # answer): this way's premise fails before the question is answered, and holding it is
            # decided by the ways with it held, tried first.
            for j in range(len(couplings)):
                if j != k and couplings[j].can_slip:
                    cannot = cannot | (let_go[j] & (parting_then(j) < 0.0))
        # (at zero, others hold its sides together: letting it go changes nothing it could carry)
        cannot_hold.append(jnp.isfinite(limit) & cannot)
        parting_ok.append(parting >= 0.0)
    return jnp.stack(stressed), jnp.stack(cannot_hold), jnp.stack(parting_ok), jnp.stack(torques)


def _broken(check, modes, candidate):
    """How many conditions a way of leaving the candidates breaks (0: consistent)."""
    stressed, cannot_hold, parting_ok, _ = check
    let_go = candidate & (slip_sign(modes) != 0.0)
    return jnp.sum(stressed > 1.0) + jnp.sum(let_go & ~(cannot_hold & parting_ok))


def _giving_way(layout: Layout, segment, t, met, modes, candidate):
    """The candidates decided as they would give way: all held, then one change at a time.

    The most overstressed held coupling lets go the way its torque pushes (a pawl pushed its free way
    lets go before a friction coupling that would hold once it has); else one let go that could hold after all
    holds again; else one let go whose sides part the other way slips that way.  Returns the modes
    and whether they are consistent: where several ways are, this picks the one a rising torque reaches.
    """
    couplings = layout.coupling_elements
    can_slip = jnp.asarray([c.can_slip for c in couplings])
    flipped_way = {SLIP_FORWARD: SLIP_BACKWARD, SLIP_BACKWARD: SLIP_FORWARD}

    def change(state):
        modes, count, _ = state
        check = _check(layout, segment, t, met, modes, candidate)
        stressed, cannot_hold, parting_ok, torques = check
        let_go = candidate & (slip_sign(modes) != 0.0)
        over = can_slip & (stressed > 1.0)
        worst = jnp.argmax(jnp.where(over, stressed, 0.0))
        rehold = jnp.argmax(let_go & ~cannot_hold)
        flip = jnp.argmax(let_go & ~parting_ok)
        released = jnp.where(torques[worst] > 0.0, SLIP_FORWARD, SLIP_BACKWARD)
        reversed_ = jnp.where(modes[flip] == SLIP_FORWARD, flipped_way[SLIP_FORWARD], flipped_way[SLIP_BACKWARD])
        new = jnp.where(jnp.any(over), modes.at[worst].set(released),
              jnp.where(jnp.any(let_go & ~cannot_hold), modes.at[rehold].set(STUCK),
                        modes.at[flip].set(reversed_)))
        done = _broken(check, modes, candidate) == 0
        return jnp.where(done, modes, new.astype(modes.dtype)), count + 1, done

    limit = 3 * len(couplings) + 1
    modes, _, done = jax.lax.while_loop(lambda s: ~s[2] & (s[1] < limit), change,
                                        (modes, jnp.zeros((), int), jnp.zeros((), bool)))
    return modes, done


def settle(layout: Layout, segment, t, y, modes, candidates, held=None):
    """The static check: which candidates stay stuck, which slip (and which way).

    The candidates' speeds are met (momentum kept).  A way of leaving them is consistent where every
    held coupling carries a torque within its capacity and every coupling let go can hold no longer
    and slips the way its sides part.  The way the couplings give way (:func:`_giving_way`) is taken if
    it is consistent; else every way is tried, the fewest let go first (:func:`_ways`), and the
    first consistent one taken: so whenever a consistent way exists, one is found, and a set of
    couplings that hold each other (a chain locking in a cascade) is decided together, not one by
    one.  Each search is one loop whose body is one try, however many couplings there are.  Should no
    way be consistent (round-off at an exact tie), the one that breaks the fewest conditions is
    taken.  ``held``: the relative speed each coupling holds (a drive's, :meth:`Instant.held_speeds`; None: no
    drives).  Returns the new modes and the met speeds.
    """
    met = keep_momentum(layout, y, candidates, held)
    couplings = layout.coupling_elements
    if not couplings:
        return modes, met
    candidate = jnp.stack([jnp.asarray(c) for c in candidates])
    held = jnp.where(candidate, STUCK, modes).astype(modes.dtype)
    path, consistent = _giving_way(layout, segment, t, met, held, candidate)
    ways = jnp.asarray(_ways(tuple(c.can_slip for c in couplings)))
    # a coupling may be let go only where it is a candidate, a contact only forwards (off its support)
    forwards_only = jnp.asarray([c.gap(Instant(layout, t, y)) is not None for c in couplings])

    def allowed(row):
        digits = ways[row]
        return jnp.all((digits == 0) | (candidate & ((digits == 1) | ~forwards_only)))

    def next_way(row):
        return jax.lax.while_loop(lambda r: (r < ways.shape[0]) & ~allowed(r), lambda r: r + 1, row)

    def modes_of(row):
        digits = ways[row]
        return jnp.where(digits == 1, SLIP_FORWARD, jnp.where(digits == 2, SLIP_BACKWARD, held)).astype(modes.dtype)

    def try_way(state):
        row, best, fewest = state
        broken = _broken(_check(layout, segment, t, met, modes_of(row), candidate), modes_of(row), candidate)
        better = broken < fewest
        return next_way(row + 1), jnp.where(better, row, best), jnp.where(better, broken, fewest)

    first = next_way(jnp.zeros((), int))
    # searched only where giving way is not consistent (a vmapped lane that needs none stops at once)
    fewest = jnp.where(consistent, 0, np.iinfo(np.int32).max)
    _, best, _ = jax.lax.while_loop(lambda s: (s[0] < ways.shape[0]) & (s[2] > 0), try_way,
                                    (first, first, fewest))
    return jnp.where(consistent, path, modes_of(best)), met


def margins(layout: Layout, segment, t, y, modes):
    """Capacity less |torque| of each coupling were it stuck at (t, y), the others as they are (N*m).

    One coupling's check, vmapped over the couplings: one copy of it in the program."""
    couplings = layout.coupling_elements
    if not couplings:
        return jnp.zeros((0,))

    def one(k):
        x = Instant(layout, t, y, modes.at[k].set(STUCK), segment.table)
        torque = x.coupling_torques[k]
        capacity = jnp.stack([jnp.asarray(c.capacity_toward(x, jnp.sign(torque)), dtype=jnp.float64)
                              for c in couplings])[k]
        return capacity - jnp.abs(torque)

    return jax.vmap(one)(jnp.arange(len(couplings)))

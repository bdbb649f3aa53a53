"""The one restart loop: a stepped pass between switches, inside a single compiled call.

Each pass of the loop integrates the current modes from the current time to
the next scheduled boundary (a table knot, an element's scheduled time, the
end), stopping early where a guard reaches zero (:mod:`.stepping`); the event
time is found by root-finding on the step's own interpolant.  The switch is decided
where the next pass starts, with a boundary's decision (:mod:`.decisions`: one static
check a step), and the loop goes on.  The loop names no part of the
machine: it asks the elements (through :class:`Layout`) for bodies, states,
couplings, guards, boundaries, observations and summaries.  Every number is a
traced input of :class:`Plan`: a new value reuses the compiled loop.
"""

from __future__ import annotations

import dataclasses
import functools

import diffrax
import equinox as eqx
import jax
import jax.numpy as jnp

from ..._pytree import pytree_dataclass
from . import decisions, extremes, guard_roles, private_api, switching
from .bodies import Response, response
from .columns import row_outputs, summary_values
from .dynamics import Instant, slip_sign
from .element import STUCK
from .eventlog import LOG_FIELDS, unpack
from .guard_id import (BREAKAWAY_BACKWARD, BREAKAWAY_FORWARD, MARGIN_VALLEY, MARGIN_VALLEYS_EACH_WAY, SLIP_VALLEY,
                       GuardId)
from .kept_steps import Steps, no_steps, rows_from_steps
from .layout import Layout
from .ledger import ledger_values
from .plan import CHATTERING, KINK_BUDGET, OK, SOLVER_FAILED, TOO_MANY_SEGMENTS, Plan, segment_budget
from .readout import RawRun
from .schedule import Segment, segment_from
from .stepping import integrate_pass

# The solvers a run may use, by the names a scenario gives them (simulation.solver: the schema's list, which
# tests/test_layers.py holds equal to this one).
SOLVERS = {"tsit5": diffrax.Tsit5, "dopri5": diffrax.Dopri5, "dopri8": diffrax.Dopri8, "bosh3": diffrax.Bosh3,
           "heun": diffrax.Heun, "kvaerno3": diffrax.Kvaerno3, "kvaerno5": diffrax.Kvaerno5}

MAX_STEPS_PER_SEGMENT = 200_000
MAX_SHRINKS = 3  # times a pass is solved again with shorter steps for crossings found in one step

# Incremented each time the loop is traced (i.e. compiled): tests use it to show
# that new parameter values do not recompile.
trace_count = 0


@pytree_dataclass
class Args:
    """What the vector field and the guards read during one pass."""

    elements: tuple
    segment: Segment
    modes: jax.Array
    observing: jax.Array
    speed_scale: jax.Array
    reply: Response | None  # the bodies' response while these modes hold (None: worked out at each call)
    offsets: dict  # observation, valley and kink guards -> what is taken off them this pass (see switching)
    kinking: jax.Array  # whether kinks still stop the integration (their budget is not spent)
    anchors: dict  # knot coordinates where the pass started (see switching.guards)
    orients: dict  # two-way observations -> +1 or -1: the way each leaves where the pass started
    switches_from: object = None  # s: switch guards held off before this time (None: never; see _step)
    # The elements' layout, worked out where the arguments are made, in the trace they belong to: one first
    # worked out inside another trace (diffrax finds a pass's first step under eval_shape) would keep that
    # trace's values (a shaft's speed ratio) and leak them into the loop.  Not a pytree field: made again
    # wherever the arguments are (their pytree unflattened calls the constructor).
    layout: Layout = dataclasses.field(init=False, repr=False, compare=False)

    def __post_init__(self):
        object.__setattr__(self, "layout", Layout(self.elements))


class _Carry(eqx.Module):
    t: jax.Array
    y: jax.Array
    modes: jax.Array
    at_boundary: jax.Array
    status: jax.Array
    switches: jax.Array
    segments: jax.Array
    steps: jax.Array
    rejected: jax.Array
    kept: Steps | None  # the accepted steps, for the output rows written after the loop (None: no rows)
    kept_count: jax.Array  # how many of them are kept (steps of a pass solved again are dropped)
    log_count: jax.Array
    kind_counts: jax.Array  # events of each kind so far (Layout.event_kinds)
    log: jax.Array  # (rows, LOG_FIELDS + states + couplings): one buffer, one write per event (see eventlog.record)
    observations: jax.Array
    kinks: jax.Array  # passes ended at a kink
    cycle_start: jax.Array  # switches, observations and kinks when the last cycle began (see AbstractElement.cycles)
    step_cap: jax.Array  # s: the largest step allowed (inf but while re-solving a missed crossing)
    shrinks: jax.Array  # times the pass now under way was solved again for crossings found together
    cap_until: jax.Array  # s: up to where the steps are capped (the crossing that sent the pass back; else inf)
    switches_from: jax.Array  # s: switches held off before this time (-inf but while re-solving for a limit)
    fired: jax.Array  # (guards,): the observations, limits and valleys that ended the last pass (guard_roles.lowerable)
    # a switch located at the end of the last pass, to be decided at the start of the next (see _decide)
    pending: jax.Array
    pending_modes: jax.Array  # the couplings' modes as the guards that fired leave them
    pending_candidates: jax.Array  # which couplings the static check decides
    extremes: dict  # running reductions of the run, for its summary (exact: every extremum is a row)
    reply: Response | None  # the bodies' response while the modes hold (None where an inertia varies)
    step_guess: jax.Array  # s: the first step of the next pass, carried over from the last (NaN: guess afresh)


def _instant(plan: Plan, segment: Segment, t, y, modes, reply=None) -> Instant:
    return Instant(plan.layout, t, y, modes, segment.table, reply=reply)


def _note(plan: Plan, segment: Segment, c: _Carry, t, y, modes, reply=None) -> tuple[_Carry, dict]:
    """Fold the state at (t, y, modes) into the run's running extremes; and whether each duration's
    condition holds there (it holds over the pass that starts there)."""
    out, holding = extremes.folded(c.extremes, plan.layout, _instant(plan, segment, t, y, modes, reply))
    return eqx.tree_at(lambda k: k.extremes, c, out), holding


def _in_cycle(c: _Carry):
    """Switches, observations and kinks since the current cycle began (the whole run if none)."""
    spent = jnp.stack([c.switches, c.observations, c.kinks]) - c.cycle_start
    return spent[0], spent[1], spent[2]


def _solve_segment(plan: Plan, segment: Segment, c: _Carry, solver, guards, reply, lanes: bool, passed_over):
    _, observations, kinks = _in_cycle(c)
    observing = observations < plan.max_switches
    kinking = kinks < KINK_BUDGET * plan.max_switches
    anchors = switching.kink_anchors(plan.layout, lambda t, y: _instant(plan, segment, t, y, c.modes, reply), c.t, c.y)
    lowerable = guard_roles.lowerable(guards)
    unset = {name: jnp.zeros(()) for i, (_, name, _) in enumerate(guards) if lowerable[i]}
    orients = switching.orients(plan.layout, c.t, c.y,
                                Args(plan.elements, segment, c.modes, observing, plan.speed_scale, reply, unset,
                                     kinking, anchors, {}))
    args = Args(plan.elements, segment, c.modes, observing, plan.speed_scale, reply, unset, kinking, anchors, orients)
    # a guard that ended the last pass starts this one at or below zero (see switching)
    unlowered = switching.guard_values(c.t, c.y, args)
    lowered_by = jnp.where(c.fired, jnp.maximum(unlowered, 0.0), 0.0)
    offsets = {name: lowered_by[i] for i, (_, name, _) in enumerate(guards) if lowerable[i]}
    # the pass ends at the segment's end, or where a pass solved again for a limit must stop (see _step)
    end = jnp.where(jnp.isneginf(c.switches_from), segment.end, jnp.minimum(segment.end, c.switches_from))
    pass_args = Args(plan.elements, segment, c.modes, observing, plan.speed_scale, reply, offsets, kinking, anchors,
                     args.orients, c.switches_from)
    # The guards where the pass starts (those above zero are armed: switching.crossed_together), worked out from
    # ``unlowered`` rather than read again: a lowered guard is its value less its offset, max(value, 0), so
    # min(value, 0), at or below zero (read again, in another copy of the guards that XLA may round apart, it
    # read a hair above zero, armed, and fired again at once on its own root: an energy minimum of the slider
    # crank found twice, 1.3e-15 s apart); a switch held off is 1 (the pass starts before the instant it is
    # held off to).
    held_off = guard_roles.of_role(guards, "switch") & jnp.isfinite(c.switches_from)
    starting = jnp.where(c.fired, jnp.minimum(unlowered, 0.0), jnp.where(held_off, 1.0, unlowered))
    return pass_args, starting, integrate_pass(
        solver, pass_args, switching.guard_values, c.t, c.y, end,
        rtol=plan.rtol, atol=plan.atol, dtmax=c.step_cap, cap_until=c.cap_until, max_steps=MAX_STEPS_PER_SEGMENT,
        kept=c.kept, count=c.kept_count, modes=c.modes, first_step=c.step_guess, bends=guard_roles.bends(guards),
        slopes0=guard_roles.bend_slopes(plan.layout, guards, anchors, kinking),
        values0=starting, crossing_step_kept=not lanes, passed_over=passed_over,
        partners=guard_roles.knot_partners(plan.layout, guards), longest=_longest_step(plan))


def _longest_step(plan: Plan):
    """The longest step the machine's torques in time allow (s; inf: any)."""
    limits = [limit for limit in (e.longest_step() for e in plan.elements) if limit is not None]
    return functools.reduce(jnp.minimum, limits, jnp.full((), jnp.inf))


def _decided(plan: Plan, segment: Segment, c: _Carry, columns: bool, lanes: bool) -> _Carry:
    """The modes for the pass that starts here and the bodies' response to them, worked out where a decision
    is due (a boundary, or a switch located where the last pass ended) and carried as they are elsewhere: a pass
    that ended at an observation, a valley or a kink changed nothing a decision reads (decide would leave the
    modes, the state and the log as they are, at the price of a static check and a response a pass).

    ``lanes``: the run is one lane of a vectorised sweep, where some lane is due at almost every pass and the
    conditional would only carry the whole loop's state (its event log) through a branch: decided at every
    pass, as a decision that is not due changes nothing."""
    layout = plan.layout

    def decide(k: _Carry) -> _Carry:
        decided = decisions.decide(plan, segment, k, columns)
        # one response per mode set; none where an inertia varies (worked out at each use); where the modes
        # change or speeds jump, the rates jump too: the first step is guessed from the new ones
        same = jnp.all(decided.modes == k.modes) & jnp.all(decided.y == k.y)
        return eqx.tree_at(lambda q: (q.reply, q.step_guess), decided,
                           (_response(layout, decided.modes), jnp.where(same, k.step_guess, jnp.nan)),
                           is_leaf=lambda x: x is None)

    if lanes:
        return decide(c)
    due = private_api.unvmap_any(c.at_boundary | c.pending)
    return jax.lax.cond(due, decide, lambda k: k, c)


def _response(layout: Layout, modes) -> Response | None:
    """The bodies' response while ``modes`` hold, or None where an inertia varies (worked out at each use)."""
    return None if layout.inertia_varies else response(layout, modes)


def _step(plan: Plan, solver, columns: bool, lanes: bool, c: _Carry) -> _Carry:
    layout = plan.layout
    guards = switching.guards(layout)
    segment = segment_from(plan.elements, plan.boundaries, plan.duration, c.t)
    c = _decided(plan, segment, c, columns, lanes)
    reply = c.reply
    c, durations = _note(plan, segment, c, c.t, c.y, c.modes, reply)
    start_t, start_y = c.t, c.y
    passed_over = guard_roles.passed_over(layout, guards)  # the knots the pass steps over (a constant mask)
    pass_args, starting, sol = _solve_segment(plan, segment, c, solver, guards, reply, lanes, passed_over)

    t_end, y_end, hit, failed = sol.t, sol.y, sol.hit, sol.failed
    masks = {name: sol.mask[i] for i, (_, name, _) in enumerate(guards)}
    # A slip valley of the wrong sign: the crossing fell inside one step and was
    # missed.  Throw this pass away and solve again from its start with steps
    # capped well below the dip's length, so that a step ends inside it.
    # Likewise a stuck coupling over its capacity at its margin's valley: it broke away within the step.
    end = Instant(layout, t_end, y_end)
    missed = jnp.zeros((), bool)
    at_end = sol.values
    by_name = {name: at_end[i] for i, (_, name, _) in enumerate(guards)}
    margin_valley, over = jnp.zeros((), bool), jnp.zeros((), bool)
    for k, coupling in enumerate(layout.coupling_elements):
        if coupling.can_slip:
            name = coupling.section
            gap = coupling.gap(end)  # a contact's sides passed through each other
            wrong = slip_sign(c.modes[k]) * end.relative_speed(name) < 0 if gap is None else gap < 0
            missed = missed | (masks[GuardId(name, SLIP_VALLEY)] & wrong)
            # (one valley is located where several couplings' margins dip at once: any of them may be over)
            for kind in MARGIN_VALLEYS_EACH_WAY if coupling.margin_each_way else (MARGIN_VALLEY,):
                margin_valley = margin_valley | masks[GuardId(name, kind)]
            over = (over | (by_name[GuardId(name, BREAKAWAY_FORWARD)] < 0.0)
                    | (by_name[GuardId(name, BREAKAWAY_BACKWARD)] < 0.0))
    missed = missed | (margin_valley & over)
    events = {GuardId(e.section, kind) for e in layout.elements for kind in e.crossing_events}
    overtaken, limit_overtaken, reached = switching.crossed_together(
        guards, at_end, starting, sol.mask, events, passed_over)
    # An observation or a limit below zero at the switch located, yet not the crossing found (it crossed and
    # came back within the step, so that only part of the step showed it): the pass is solved again once, only
    # up to that switch's instant and with the switches held off, so that its own root is found; the next
    # pass meets the switch again.  (Should it
    # not cross on the way after all, the pass ends there as at a boundary, where the modes are decided anew.)
    located_switch = jnp.any(sol.mask & guard_roles.of_role(guards, "switch"))
    found_first = hit & located_switch & (overtaken | limit_overtaken) & ~missed & jnp.isneginf(c.switches_from)
    cap = jnp.minimum(c.step_cap, t_end - start_t) / 8.0
    # else the pass is solved again with shorter steps (at most three times), so that each crossing has a step.
    # The times are counted: each pass solved again may find its crossing sooner, so that its own length, and
    # with it the bound on the cap, shrinks with the cap (guards at round-off could then shrink it for ever,
    # and the pass that no longer crosses would creep to its end at the last cap)
    shrink = missed | (hit & overtaken & ~found_first & (cap * 8.0**3 >= t_end - start_t)
                       & (c.shrinks < MAX_SHRINKS))
    missed = shrink | found_first
    kept = ~missed
    # (on the guard vector: a scalar made of many, ``kept``, taken into one operation a guard would be copied
    # into each by XLA, a program that grows as the guards times the couplings)
    located = sol.mask & kept
    masks = {name: located[i] for i, (_, name, _) in enumerate(guards)}
    # the pass's steps are kept for the rows, unless it is solved again (they are written over)
    kept_count = jnp.where(kept, sol.count, c.kept_count)
    y_end = jnp.where(missed, start_y, y_end)
    t_reached = jnp.where(missed, start_t, t_end)
    c, _ = _note(plan, segment, c, t_reached, y_end, c.modes, reply)
    spent = jnp.where(~failed & kept, t_end - start_t, 0.0)
    running = dict(c.extremes, **{name: c.extremes[name] + jnp.where(on, spent, 0.0)
                                  for name, on in durations.items()})
    reached = reached & kept
    told = guard_roles.reported(guards, events)
    coinciding = {name: reached[i] for i, (_, name, _) in enumerate(guards) if told[i]}
    # a limit recorded where another guard was located has ended this pass as if it had fired; a pass thrown
    # away leaves what ended the one before it as it was (its guard starts the pass solved again lowered)
    fired = jnp.where(kept, (located | reached) & guard_roles.lowerable(guards), c.fired)
    c = eqx.tree_at(
        lambda k: (k.extremes, k.kept, k.kept_count, k.steps, k.rejected, k.segments, k.fired),
        c,
        (running, sol.kept, kept_count, c.steps + sol.steps, c.rejected + sol.rejected, c.segments + 1, fired),
        is_leaf=lambda x: x is None,
    )
    c = decisions.apply_event(plan, segment, eqx.tree_at(lambda k: k.y, c, y_end), t_end, y_end, masks, hit & kept,
                     coinciding, pass_args.orients)
    at_knot = jnp.any(located & guard_roles.of_role(guards, "kink"))
    switches, _, _ = _in_cycle(c)
    status = jnp.where(failed, SOLVER_FAILED, jnp.where(switches > plan.max_switches, CHATTERING, c.status))
    return eqx.tree_at(
        lambda k: (k.t, k.at_boundary, k.status, k.step_cap, k.shrinks, k.cap_until, k.switches_from, k.step_guess),
        c,
        (t_reached, kept & (~hit | (t_end >= segment.end)), status,
         jnp.where(shrink, cap, jnp.inf), jnp.where(shrink, c.shrinks + 1, 0), jnp.where(shrink, t_end, jnp.inf),
         # (a pass solved again with the switches held off keeps them held off through its shorter steps: let
         # go, it would locate the switch first again and be solved again held off, without end)
         jnp.where(found_first, t_end, jnp.where(shrink, c.switches_from, -jnp.inf)),
         # a pass that ended at a table's knot (the rate bends there, nothing jumps) hands its steps on; after
         # anything else the next pass guesses its own (after an observation or a valley too: a machine held at
         # rest has nothing to bound its steps but that fresh start, and a step grown over a whole swing of a
         # torque would pass a margin's valley unseen)
         jnp.where(at_knot, sol.proposed, jnp.nan)),
    )


def restart_loop(plan: Plan, solver, log_size: int, step_room: int = 0, columns: bool = True,
                 lanes: bool = False) -> RawRun:
    """One run of ``plan``, traced: jitted by :func:`compiled_run`, vectorised over a sweep's runs by
    :func:`hoistsim.running.blocks.compiled_batch`; ``columns`` False leaves out the output rows and columns (a
    summary-only sweep needs none); ``lanes`` True, one lane of that vectorised sweep (see ``_decided``).  The
    rows are written after the loop from the accepted steps it kept (room for ``step_room``; a run that takes
    more is taken again with room for them all: counters say)."""
    global trace_count
    trace_count += 1
    layout = plan.layout
    rows, size, couplings = plan.grid.shape[0], layout.size, len(layout.couplings)
    nan = jnp.nan
    c = _Carry(
        t=jnp.zeros(()),
        y=plan.initial_state,
        modes=jnp.full((couplings,), STUCK),
        at_boundary=jnp.array(True),
        status=jnp.array(OK),
        switches=jnp.array(0),
        segments=jnp.array(0),
        steps=jnp.array(0),
        rejected=jnp.array(0),
        kept=no_steps(solver, plan.initial_state, step_room, couplings) if columns and step_room else None,
        kept_count=jnp.array(0),
        log_count=jnp.array(0),
        kind_counts=jnp.zeros((len(layout.event_kinds),), int),
        log=jnp.full((log_size, LOG_FIELDS + (size if columns else 0) + couplings), nan),
        observations=jnp.array(0),
        kinks=jnp.array(0),
        cycle_start=jnp.zeros((3,), int),
        step_cap=jnp.full((), jnp.inf),
        shrinks=jnp.array(0),
        cap_until=jnp.full((), jnp.inf),
        switches_from=jnp.full((), -jnp.inf),
        fired=jnp.zeros((len(switching.guards(layout)),), bool),
        pending=jnp.array(False),
        pending_modes=jnp.full((couplings,), STUCK),
        pending_candidates=jnp.zeros((couplings,), bool),
        extremes=extremes.initial_extremes(layout, plan.initial_state),
        reply=_response(layout, jnp.full((couplings,), STUCK)),
        step_guess=jnp.full((), jnp.nan),
    )

    max_segments = segment_budget(plan)

    def going(c: _Carry):
        # a switch located at the very end is still decided (a pass of no length follows it)
        return ((c.t < plan.duration) | c.pending) & (c.status == OK) & (c.segments < max_segments)

    # The kept steps and the event log are buffers of the run's loop too: written in place (see stepping).
    c = private_api.while_loop(going, functools.partial(_step, plan, solver, columns, lanes), c, kind="lax",
                               buffers=lambda k: (k.kept, k.log))
    status = jnp.where((c.status == OK) & (c.t < plan.duration), TOO_MANY_SEGMENTS, c.status)
    # The rows: before where the run ended, on the steps that cover them; from there on (the duration, the
    # grid's padding), the final state (nothing where the run failed).
    ended = (plan.grid >= c.t)[:, None]
    if c.kept is not None:
        stepped_state, stepped_modes = rows_from_steps(solver, c.kept, c.kept_count, plan.grid)
    else:  # no row before the end (a summary's one row): no steps kept
        stepped_state, stepped_modes = jnp.full((rows, size), nan), jnp.full((rows, couplings), -1)
    grid_state = jnp.where(ended, jnp.where(status == OK, c.y, nan), stepped_state)
    grid_modes = jnp.where(ended, jnp.where(status == OK, c.modes, -1), stepped_modes)
    # the ledger's scale: the most kinetic energy at a pass's ends or a row (a run that swings and comes to rest
    # again, its works cancelling, without a switch between)
    peak = c.extremes[extremes.KINETIC_PEAK]
    if c.kept is not None:
        held = jax.vmap(lambda y: Instant(layout, 0.0, y).kinetic_energy())(stepped_state)
        peak = jnp.maximum(peak, jnp.max(jnp.where(ended[:, 0] | jnp.isnan(held), 0.0, held)))
    scalars = [c.t, *summary_values(plan, c.extremes, c.y, c.modes), *ledger_values(layout, plan.initial_state),
               *ledger_values(layout, c.y), peak]
    log_time, log_margin, codes, log_state, log_modes = unpack(c.log, c.log_count, couplings, columns)
    # the grid's rows and the events' through one evaluation (one copy of it in the program)
    outputs = row_outputs(plan, jnp.concatenate([plan.grid, log_time]), jnp.concatenate([grid_state, log_state]),
                          jnp.concatenate([grid_modes, log_modes])) if columns else jnp.zeros((0, rows + log_size))
    return RawRun(
        grid_state=grid_state,
        grid_modes=grid_modes,
        grid_columns=outputs[:, :rows],
        event_columns=outputs[:, rows:],
        event_times=jnp.stack([log_time, log_margin], axis=1),
        event_codes=codes,
        event_state=log_state,
        event_modes=log_modes,
        final_state=c.y,
        scalars=jnp.stack([jnp.asarray(v, dtype=jnp.float64) for v in scalars]),
        counters=jnp.stack([c.log_count, c.switches, status, c.steps, c.rejected, c.segments, c.kept_count,
                            step_room]),
        kind_counts=c.kind_counts,
    )


@functools.lru_cache(maxsize=None)
def compiled_run(solver_name: str, log_size: int, step_room: int, columns: bool = True):
    """The jitted loop for a solver, its event log's rows and the steps it keeps; shapes of the plan select the
    rest."""
    solver = SOLVERS[solver_name]()
    return jax.jit(functools.partial(restart_loop, solver=solver, log_size=log_size, step_room=step_room,
                                     columns=columns))

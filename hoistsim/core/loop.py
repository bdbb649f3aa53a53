"""The one restart loop: a stepped pass between switches, inside a single compiled call.

Each pass of the loop integrates the current modes from the current time to
the next scheduled boundary (a table knot, an element's scheduled time, the
end), stopping early where a guard reaches zero (:mod:`.stepping`); the event
time is found by root-finding on the step's own interpolant.  The switch is then applied
(reset + new modes) and the loop goes on.  The loop names no part of the
machine: it asks the elements (through :class:`Layout`) for bodies, states,
couplings, guards, boundaries, observations and summaries.  Every number is a
traced input of :class:`Plan`: a new value reuses the compiled loop.
"""

from __future__ import annotations

import functools
from functools import cached_property

import diffrax
import equinox as eqx
import jax
import jax.numpy as jnp

from .._pytree import pytree_dataclass
from ..schema import SOLVERS as SOLVER_NAMES
from . import static_check, switching
from .bodies import Response, keep_momentum, response, response_table
from .dynamics import Instant, slip_sign, vector_field
from .element import SLIP_BACKWARD, SLIP_FORWARD, SLIP_RESOLUTION, STUCK
from .layout import NO_EVENT, SWITCH_KINDS, Layout
from .columns import row_outputs, summary_values
from .eventlog import LOG_FIELDS, record, unpack
from .ledger import ledger_values
from .readout import RawRun
from .schedule import Segment, segment_from
from .stepping import integrate_pass

OK, CHATTERING, SOLVER_FAILED, TOO_MANY_SEGMENTS = range(4)
STATUS_TEXT = {OK: "ok", CHATTERING: "chattering", SOLVER_FAILED: "solver failed",
               TOO_MANY_SEGMENTS: "too many segments"}

# The names a scenario accepts (schema.SOLVERS) are diffrax's class names in lower case.
SOLVERS = {name: getattr(diffrax, name.capitalize()) for name in SOLVER_NAMES}

MAX_STEPS_PER_SEGMENT = 200_000
# Where one coupling's sides meet, another's meet at the same instant if their relative speed is within
# this many slip resolutions (the round-off of the located root).
SHARED_ZERO = 16
# Passes that may end at a kink, per allowed switch (beyond, kinks are stepped across).
KINK_BUDGET = 100
_REDUCTIONS = {"max": -jnp.inf, "min": jnp.inf, "first": jnp.nan, "first_value": jnp.nan, "duration": 0.0}

# Incremented each time the loop is traced (i.e. compiled): tests use it to show
# that new parameter values do not recompile.
trace_count = 0


@pytree_dataclass
class Plan:
    """Everything one run needs, as arrays: the traced inputs of the compiled loop."""

    elements: tuple
    boundaries: jax.Array  # s, scheduled segment boundaries (any order, within [0, duration])
    initial_state: jax.Array  # named by Layout(elements).state_names
    speed_scale: jax.Array  # rad/s, for the slip resolution
    duration: jax.Array  # s
    grid: jax.Array  # s, output times (padded with the duration)
    rtol: jax.Array
    atol: jax.Array
    max_switches: jax.Array  # mode switches allowed before the run counts as chattering

    @cached_property
    def layout(self) -> Layout:
        return Layout(self.elements)


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

    @cached_property
    def layout(self) -> Layout:
        return Layout(self.elements)


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
    grid_state: jax.Array
    grid_modes: jax.Array
    log_count: jax.Array
    kind_counts: jax.Array  # events of each kind so far (Layout.event_kinds)
    log: jax.Array  # (rows, LOG_FIELDS + states + couplings): one buffer, one write per event (see eventlog.record)
    observations: jax.Array
    kinks: jax.Array  # passes ended at a kink
    cycle_start: jax.Array  # switches, observations and kinks when the last cycle began (see AbstractElement.cycles)
    step_cap: jax.Array  # s: the largest step allowed (inf but while re-solving a missed crossing)
    switches_from: jax.Array  # s: switches held off before this time (-inf but while re-solving for a limit)
    fired: dict  # observation and valley guards -> whether one ended the last pass
    extremes: dict  # running reductions of the run, for its summary (exact: every extremum is a row)


def _instant(plan: Plan, segment: Segment, t, y, modes, reply=None) -> Instant:
    return Instant(plan.layout, t, y, modes, segment.table, reply=reply)


def _reductions(plan: Plan, x: Instant) -> dict:
    out = {}
    for element in plan.layout.elements:
        out.update(element.extremes(x))
    return out


def _note(plan: Plan, segment: Segment, c: _Carry, t, y, modes, reply=None) -> _Carry:
    """Fold the state at (t, y, modes) into the run's running extremes."""
    folded = {}
    for name, (kind, value) in _reductions(plan, _instant(plan, segment, t, y, modes, reply)).items():
        old = c.extremes[name]
        folded[name] = {"max": lambda: jnp.maximum(old, value), "min": lambda: jnp.minimum(old, value),
                        "first": lambda: jnp.where(jnp.isnan(old) & value, t, old),
                        "first_value": lambda: jnp.where(jnp.isnan(old) & value[0], value[1], old),
                        "duration": lambda: old}[kind]()
    return eqx.tree_at(lambda k: k.extremes, c, folded)


def _record_transitions(plan: Plan, segment: Segment, c: _Carry, when, t, y, before, after,
                        columns: bool) -> _Carry:
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


def _scheduled_switches(plan: Plan, segment: Segment, c: _Carry, columns: bool) -> _Carry:
    """At a boundary: record the elements' scheduled events, then re-decide every coupling."""
    layout = plan.layout
    modes, candidates = static_check.candidates_at_boundary(layout, segment, c.y, plan.speed_scale)
    decided, _ = static_check.settle(layout, segment, c.t, c.y, modes, candidates)
    decided_y = switching.with_impacts(layout, c.y, keep_momentum(layout, c.y, [m == STUCK for m in decided]),
                                       c.modes, decided)
    before = c.modes
    new_modes = jnp.where(c.at_boundary, decided, c.modes)
    c = eqx.tree_at(lambda k: (k.y, k.modes), c, (jnp.where(c.at_boundary, decided_y, c.y), new_modes))
    for index, element in enumerate(layout.elements):
        for kind, happens in element.boundary_events(c.t):
            c = record(c, c.at_boundary & happens, c.t, layout.kind_code(kind), index, c.y, new_modes, jnp.nan)
    # The first decision (t = 0) sets the initial modes; it is not an event.
    before = jnp.where(c.segments == 0, -1, before)
    return _record_transitions(plan, segment, c, c.at_boundary, c.t, c.y, before, new_modes, columns)


def _apply_event(plan: Plan, segment: Segment, c: _Carry, t, y, masks: dict, hit, columns: bool,
                 coinciding: dict, orients: dict) -> _Carry:
    """A guard fired at (t, y): lock, reverse or unlock with the matching reset, or an observation.

    ``coinciding``: knots reached at (t, y) along with the guard that fired; ``orients``: the way each
    two-way observation left the pass's start (+1: it fell to zero; see switching.orients).
    """
    layout = plan.layout
    # At most one guard fires at a time (the earliest; the first listed at one instant): one row for any observation.
    observed, kind, element = jnp.zeros((), bool), NO_EVENT, -1
    for role, name, _ in switching.guards(layout):
        if role in ("observe", "limit"):
            section, what = name.rsplit(".", 1)
            named = layout.elements[layout.sections.index(section)].crossing_events.get(what)
            code = layout.kind_code(what) if named is None else jnp.where(
                orients[name] > 0, layout.kind_code(named[1]), layout.kind_code(named[0]))
            kind = jnp.where(masks[name], code, kind)
            element = jnp.where(masks[name], layout.sections.index(section), element)
            observed = observed | masks[name]
    c = record(c, observed, t, kind, element, y, c.modes, jnp.nan)
    # A limit crossed at the same instant as the located guard: a row of its own, at that instant.
    for role, name, _ in switching.guards(layout):
        if role == "limit":
            section, what = name.rsplit(".", 1)
            c = record(c, coinciding[name], t, layout.kind_code(what), layout.sections.index(section), y, c.modes,
                       jnp.nan)
            c = eqx.tree_at(lambda k: k.observations, c, c.observations + coinciding[name])
    valley = functools.reduce(jnp.logical_or, [masks[n] for r, n, _ in switching.guards(layout) if r == "valley"],
                              jnp.zeros((), bool))
    kinked = functools.reduce(jnp.logical_or, [masks[n] for r, n, _ in switching.guards(layout) if r == "kink"],
                              jnp.zeros((), bool))
    # A cycle's end: a row of its kind, and the budgets start again.
    cycled = jnp.zeros((), bool)
    for index, kink, kind in layout.cycles:
        names = [f"{layout.sections[index]}.{kink}{side}" for side in "+-"]
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
        met, up, down = masks[f"{name}.slip"], masks[f"{name}.breakaway+"], masks[f"{name}.breakaway-"]
        modes = modes.at[k].set(jnp.where(up, SLIP_FORWARD, jnp.where(down, SLIP_BACKWARD,
                                                                       jnp.where(met, STUCK, modes[k]))))
        candidates[k] = (candidates[k] & ~up & ~down) | met
    # Sides that meet where another coupling's sides meet (one zero of speed shared by both, a shaft
    # stopping against two holds at once) are tried stuck too: a pass reports one guard.
    meeting = functools.reduce(jnp.logical_or, [masks[f"{e.section}.slip"] for e in layout.coupling_elements
                                                if e.can_slip], jnp.zeros((), bool))
    x = Instant(layout, t, y)
    for k, coupling in enumerate(layout.coupling_elements):
        if not coupling.can_slip:
            continue
        together = meeting & (slip_sign(modes[k]) != 0.0) & switching.touching(coupling, x) & (
            jnp.abs(x.relative_speed(coupling.section)) <= SHARED_ZERO * SLIP_RESOLUTION * plan.speed_scale)
        modes = modes.at[k].set(jnp.where(together, STUCK, modes[k]))
        candidates[k] = candidates[k] | together
    new_modes, new_y = static_check.settle(layout, segment, t, y, modes, candidates)
    new_y = switching.with_impacts(layout, y, new_y, c.modes, new_modes)
    c = _record_transitions(plan, segment, c, hit, t, new_y, c.modes, new_modes, columns)
    return eqx.tree_at(lambda k: (k.y, k.modes), c,
                       (jnp.where(hit, new_y, c.y), jnp.where(hit, new_modes, c.modes)))


def _in_cycle(c: _Carry):
    """Switches, observations and kinks since the current cycle began (the whole run if none)."""
    spent = jnp.stack([c.switches, c.observations, c.kinks]) - c.cycle_start
    return spent[0], spent[1], spent[2]


def _solve_segment(plan: Plan, segment: Segment, c: _Carry, solver, guards, reply, columns: bool):
    _, observations, kinks = _in_cycle(c)
    observing = observations < plan.max_switches
    kinking = kinks < KINK_BUDGET * plan.max_switches
    anchors = switching.kink_anchors(plan.layout, _instant(plan, segment, c.t, c.y, c.modes, reply))
    unset = {name: jnp.zeros(()) for name in c.fired}
    orients = switching.orients(plan.layout, c.t, c.y,
                                Args(plan.elements, segment, c.modes, observing, plan.speed_scale, reply, unset,
                                     kinking, anchors, {}))
    args = Args(plan.elements, segment, c.modes, observing, plan.speed_scale, reply, unset, kinking, anchors, orients)
    # a guard that ended the last pass starts this one at or below zero (see switching)
    offsets = {name: jnp.where(c.fired[name], jnp.maximum(g(c.t, c.y, args), 0.0), 0.0)
               for _, name, g in guards if name in c.fired}
    # the pass ends at the segment's end, or where a pass solved again for a limit must stop (see _step)
    end = jnp.where(jnp.isneginf(c.switches_from), segment.end, jnp.minimum(segment.end, c.switches_from))
    pass_args = Args(plan.elements, segment, c.modes, observing, plan.speed_scale, reply, offsets, kinking, anchors,
                     args.orients, c.switches_from)
    # The guards other than switches where the pass starts (those above zero are armed).
    armed = {name: g(c.t, c.y, pass_args) for role, name, g in guards if role != "switch"}
    return pass_args, armed, integrate_pass(
        solver, pass_args, lambda t, y, a: jnp.stack([g(t, y, a) for _, _, g in guards]), c.t, c.y, end,
        rtol=plan.rtol, atol=plan.atol, dtmax=c.step_cap, grid=plan.grid, grid_state=c.grid_state,
        write_rows=columns, max_steps=MAX_STEPS_PER_SEGMENT)


def _step(plan: Plan, solver, columns: bool, c: _Carry) -> _Carry:
    layout = plan.layout
    guards = switching.guards(layout)
    segment = segment_from(plan.elements, plan.boundaries, plan.duration, c.t)
    c = _scheduled_switches(plan, segment, c, columns)
    # one response per pass while the modes hold; none where an inertia varies (worked out at each use)
    reply = None if layout.inertia_varies else response(layout, c.modes)
    c = _note(plan, segment, c, c.t, c.y, c.modes, reply)
    durations = {name: value for name, (kind, value) in
                 _reductions(plan, _instant(plan, segment, c.t, c.y, c.modes, reply)).items() if kind == "duration"}
    start_t, start_y = c.t, c.y
    pass_args, armed, sol = _solve_segment(plan, segment, c, solver, guards, reply, columns)

    t_end, y_end, hit, failed = sol.t, sol.y, sol.hit, sol.failed
    masks = {name: sol.mask[i] for i, (_, name, _) in enumerate(guards)}
    # A slip valley of the wrong sign: the crossing fell inside one step and was
    # missed.  Throw this pass away and solve again from its start with steps
    # capped well below the dip's length, so that a step ends inside it.
    end = Instant(layout, t_end, y_end)
    missed = jnp.zeros((), bool)
    for k, coupling in enumerate(layout.coupling_elements):
        if coupling.can_slip:
            gap = coupling.gap(end)  # a contact's sides passed through each other
            wrong = slip_sign(c.modes[k]) * end.relative_speed(coupling.section) < 0 if gap is None else gap < 0
            missed = missed | (masks[f"{coupling.section}.slip_valley"] & wrong)
    overtaken, limit_overtaken, coinciding = switching.crossed_together(guards, pass_args, t_end, y_end, armed,
                                                                        masks)
    # An observation or a limit below zero at the switch located, yet not the crossing found (it crossed and
    # came back within the step, so that only part of the step showed it): the pass is solved again once, only
    # up to that switch's instant and with the switches held off, so that its own root is found; the next
    # pass meets the switch again.  (Should it
    # not cross on the way after all, the pass ends there as at a boundary, where the modes are decided anew.)
    located_switch = functools.reduce(jnp.logical_or, [masks[n] for r, n, _ in guards if r == "switch"],
                                      jnp.zeros((), bool))
    found_first = hit & located_switch & (overtaken | limit_overtaken) & ~missed & jnp.isneginf(c.switches_from)
    cap = jnp.minimum(c.step_cap, t_end - start_t) / 8.0
    # else the pass is solved again with shorter steps (at most three times), so that each crossing has a step
    shrink = missed | (hit & overtaken & ~found_first & (cap * 8.0**3 >= t_end - start_t))
    missed = shrink | found_first
    kept = ~missed
    masks = {name: m & kept for name, m in masks.items()}
    rows = (plan.grid >= c.t) & (plan.grid < t_end) & kept
    grid_state = jnp.where(kept, sol.grid_state, c.grid_state)
    grid_modes = jnp.where(rows[:, None], c.modes, c.grid_modes)
    y_end = jnp.where(missed, start_y, y_end)
    t_reached = jnp.where(missed, start_t, t_end)
    c = _note(plan, segment, c, t_reached, y_end, c.modes, reply)
    spent = jnp.where(~failed & kept, t_end - start_t, 0.0)
    extremes = dict(c.extremes, **{name: c.extremes[name] + jnp.where(on, spent, 0.0)
                                   for name, on in durations.items()})
    coinciding = {name: reached & kept for name, reached in coinciding.items()}
    # a limit recorded where another guard was located has ended this pass as if it had fired; a pass thrown
    # away leaves what ended the one before it as it was (its guard starts the pass solved again lowered)
    fired = {name: jnp.where(kept, masks[name] | coinciding.get(name, False), c.fired[name]) for name in c.fired}
    c = eqx.tree_at(
        lambda k: (k.extremes, k.grid_state, k.grid_modes, k.steps, k.rejected, k.segments, k.fired),
        c,
        (extremes, grid_state, grid_modes, c.steps + sol.steps, c.rejected + sol.rejected, c.segments + 1, fired),
    )
    c = _apply_event(plan, segment, eqx.tree_at(lambda k: k.y, c, y_end), t_end, y_end, masks, hit & kept,
                     columns, coinciding, pass_args.orients)
    c = _note(plan, segment, c, t_reached, c.y, c.modes)
    switches, _, _ = _in_cycle(c)
    status = jnp.where(failed, SOLVER_FAILED, jnp.where(switches > plan.max_switches, CHATTERING, c.status))
    return eqx.tree_at(
        lambda k: (k.t, k.at_boundary, k.status, k.step_cap, k.switches_from),
        c,
        (t_reached, kept & (~hit | (t_end >= segment.end)), status,
         jnp.where(shrink, cap, jnp.inf), jnp.where(found_first, t_end, -jnp.inf)),
    )


def _run(plan: Plan, solver, max_segments: int, log_size: int, columns: bool = True) -> RawRun:
    """One run; ``columns`` False leaves out the output columns (a summary-only sweep needs none)."""
    global trace_count
    trace_count += 1
    layout = plan.layout
    layout.responses = response_table(layout)  # once per run, outside the loop
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
        grid_state=jnp.full((rows, size), nan),
        grid_modes=jnp.full((rows, couplings), -1),
        log_count=jnp.array(0),
        kind_counts=jnp.zeros((len(layout.event_kinds),), int),
        log=jnp.full((log_size, LOG_FIELDS + (size if columns else 0) + couplings), nan),
        observations=jnp.array(0),
        kinks=jnp.array(0),
        cycle_start=jnp.zeros((3,), int),
        step_cap=jnp.full((), jnp.inf),
        switches_from=jnp.full((), -jnp.inf),
        fired={name: jnp.array(False) for role, name, _ in switching.guards(layout) if role in ("observe", "limit", "valley")},
        extremes=_initial_extremes(plan),
    )

    def going(c: _Carry):
        return (c.t < plan.duration) & (c.status == OK) & (c.segments < max_segments)

    c = jax.lax.while_loop(going, functools.partial(_step, plan, solver, columns), c)
    status = jnp.where((c.status == OK) & (c.t < plan.duration), TOO_MANY_SEGMENTS, c.status)
    # The end of the run: rows at the duration (and the grid's padding) take the final state.
    last = plan.grid >= c.t
    grid_state = jnp.where(last[:, None] & (status == OK), c.y, c.grid_state)
    grid_modes = jnp.where(last[:, None] & (status == OK), c.modes, c.grid_modes)
    scalars = [c.t, *summary_values(plan, c.extremes, c.y, c.modes), *ledger_values(layout, plan.initial_state),
               *ledger_values(layout, c.y)]
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
        counters=jnp.stack([c.log_count, c.switches, status, c.steps, c.rejected, c.segments]),
        kind_counts=c.kind_counts,
    )


def _initial_extremes(plan: Plan) -> dict:
    """Each running reduction's starting value (its identity: -inf for a max, NaN for a first time...)."""
    x = Instant(plan.layout, jnp.zeros(()), plan.initial_state, jnp.full((len(plan.layout.couplings),), STUCK),
                lambda name, t: jnp.zeros(()))
    return {name: jnp.asarray(_REDUCTIONS[kind], dtype=jnp.float64) for name, (kind, _) in
            _reductions(plan, x).items()}


@functools.lru_cache(maxsize=None)
def compiled_run(solver_name: str, max_segments: int, log_size: int, columns: bool = True):
    """The jitted loop for a solver and buffer sizes; shapes of the plan select the rest."""
    solver = SOLVERS[solver_name]()
    return jax.jit(functools.partial(_run, solver=solver, max_segments=max_segments, log_size=log_size,
                                     columns=columns))

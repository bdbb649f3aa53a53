"""The one restart loop: diffeqsolve between switches, inside a single compiled call.

Each pass of the loop integrates the current mode from the current time to the
next scheduled boundary (a kink or step of the force table, the brake release,
the end), stopping early where a guard of the mode reaches zero; the event time
is found by root-finding on the solver's dense interpolant.  The switch is then
applied (reset + new mode) and the loop goes on.  Force, load and every other
number are traced inputs of :class:`Plan`: a new value reuses the compiled loop.
"""

from __future__ import annotations

import functools

import diffrax
import equinox as eqx
import jax
import jax.numpy as jnp

from . import clutch_modes as cm
from ._pytree import pytree_dataclass
from .schema import SOLVERS as SOLVER_NAMES
from .model import LOCKED, OPEN, SLIP_RESOLUTION, Drivetrain, force_at
from .rootfind import CrossingBisection
from .series import drum_held, row_outputs

OK, CHATTERING, SOLVER_FAILED, TOO_MANY_SEGMENTS = range(4)
STATUS_TEXT = {
    OK: "ok",
    CHATTERING: "chattering",
    SOLVER_FAILED: "solver failed",
    TOO_MANY_SEGMENTS: "too many segments",
}

# The names a scenario accepts (schema.SOLVERS) are diffrax's class names in lower case.
SOLVERS = {name: getattr(diffrax, name.capitalize()) for name in SOLVER_NAMES}

MAX_STEPS_PER_SEGMENT = 200_000

# Incremented each time the loop is traced (i.e. compiled): tests use it to show
# that new parameter values do not recompile.
trace_count = 0


@pytree_dataclass
class Plan:
    """Everything one run needs, as arrays: the traced inputs of the compiled loop."""

    drivetrain: Drivetrain
    force_times: jax.Array  # s, the engagement force table
    force_values: jax.Array  # N
    effects: tuple
    boundaries: jax.Array  # s, scheduled segment boundaries (any order, within [0, duration])
    initial_state: jax.Array  # see clutch_modes for the layout
    duration: jax.Array  # s
    grid: jax.Array  # s, output times (padded with the duration)
    rtol: jax.Array
    atol: jax.Array
    max_switches: jax.Array  # mode switches allowed before the run counts as chattering


@pytree_dataclass
class RawRun:
    """What the compiled loop returns; :mod:`hoistsim.simulation` turns it into a result."""

    grid_state: jax.Array  # (rows, STATE_SIZE)
    grid_mode: jax.Array  # (rows,)
    grid_outputs: dict  # name -> (rows,)
    event_outputs: dict  # name -> (events,)
    event_time: jax.Array  # (events,), NaN where unused
    event_kind: jax.Array
    event_state: jax.Array
    event_mode: jax.Array
    event_margin: jax.Array  # N*m: static capacity minus |locked torque| at the event
    event_count: jax.Array
    final_state: jax.Array
    extremes: dict  # lockup_time, slip_duration, peak_clutch_torque, peak_slip_speed, lowest_load_position
    switch_count: jax.Array
    status: jax.Array
    end_time: jax.Array
    steps: jax.Array
    rejected_steps: jax.Array
    segments: jax.Array


def segment_from(plan: Plan, t0) -> cm.Segment:
    """The segment starting at t0: its end, its force line and whether the drum is held."""
    later = jnp.where(plan.boundaries > t0, plan.boundaries, plan.duration)
    t1 = jnp.minimum(jnp.min(later), plan.duration)
    middle = 0.5 * (t0 + t1)
    times, values = plan.force_times, plan.force_values
    if times.shape[0] == 1:
        force_start, slope = values[0], jnp.zeros_like(values[0])
    else:
        # The table interval holding the middle of the segment gives its line, so a
        # step at either end belongs to the neighbouring segment.
        k = jnp.clip(jnp.searchsorted(times, middle, side="right") - 1, 0, times.shape[0] - 2)
        width = times[k + 1] - times[k]
        inside = (middle >= times[0]) & (middle < times[-1]) & (width > 0)
        slope = jnp.where(inside, (values[k + 1] - values[k]) / jnp.where(width > 0, width, 1.0), 0.0)
        force_start = jnp.where(inside, values[k] + slope * (t0 - times[k]),
                                force_at(times, values, middle, jnp))
    force_end = force_start + slope * (t1 - t0)
    return cm.Segment(
        start=t0,
        end=t1,
        force_start=force_start,
        force_slope=slope,
        drum_held=drum_held(plan.effects, middle),
        is_open=(force_start == 0.0) & (force_end == 0.0),
    )


def decide_at_boundary(plan: Plan, segment: cm.Segment, t, y):
    """Mode at a scheduled boundary: open with no force, else by slip sign, else the static check.

    Returns the mode and the state, whose speeds are made one when a (negligible)
    slip is declared locked.
    """
    slip = y[cm.MOTOR_SPEED] - y[cm.OUTPUT_SPEED]
    tiny = SLIP_RESOLUTION * plan.drivetrain.no_load_speed
    common = _common_speed(plan.drivetrain, segment, y)
    static = cm.static_check(plan.drivetrain, segment, t, common)
    mode = jnp.where(slip > tiny, cm.SLIP_FORWARD, jnp.where(slip < -tiny, cm.SLIP_BACKWARD, static))
    mode = jnp.where(segment.is_open, OPEN, mode)
    met = y.at[cm.MOTOR_SPEED].set(common).at[cm.OUTPUT_SPEED].set(common)
    return mode, jnp.where(mode == LOCKED, met, y)


def _common_speed(drivetrain, segment: cm.Segment, y):
    """The speed two sides take when they meet: momentum kept, or still while the brake holds."""
    common = (drivetrain.motor_inertia * y[cm.MOTOR_SPEED] + drivetrain.output_inertia * y[cm.OUTPUT_SPEED]) / (
        drivetrain.motor_inertia + drivetrain.output_inertia)
    return common if segment.drum_held is None else jnp.where(segment.drum_held, 0.0, common)


class _Carry(eqx.Module):
    t: jax.Array
    y: jax.Array
    mode: jax.Array
    at_boundary: jax.Array
    status: jax.Array
    switches: jax.Array
    segments: jax.Array
    steps: jax.Array
    rejected: jax.Array
    grid_state: jax.Array
    grid_mode: jax.Array
    log_count: jax.Array
    log_time: jax.Array
    log_kind: jax.Array
    log_state: jax.Array
    log_mode: jax.Array
    log_margin: jax.Array
    observations: jax.Array
    step_cap: jax.Array  # s: the largest step allowed (inf but while re-solving a missed crossing)
    # running extremes of the run, for its summary (exact: every extremum is a row)
    peak_torque: jax.Array
    peak_slip: jax.Array
    lowest_position: jax.Array
    slip_time: jax.Array
    lockup_time: jax.Array


def _note(plan: Plan, segment: cm.Segment, c: _Carry, t, y, mode) -> _Carry:
    """Fold the state at (t, y, mode) into the run's running extremes."""
    r = cm.rates(plan.drivetrain, mode, segment.engagement_force(t), y[cm.MOTOR_SPEED], y[cm.OUTPUT_SPEED],
                 segment.drum_held)
    first_lock = jnp.isnan(c.lockup_time) & (mode == LOCKED)
    return eqx.tree_at(
        lambda k: (k.peak_torque, k.peak_slip, k.lowest_position, k.lockup_time),
        c,
        (jnp.maximum(c.peak_torque, jnp.abs(r.clutch_torque)),
         jnp.maximum(c.peak_slip, jnp.abs(y[cm.MOTOR_SPEED] - y[cm.OUTPUT_SPEED])),
         jnp.minimum(c.lowest_position, y[cm.LOAD_POSITION]),
         jnp.where(first_lock, t, c.lockup_time)),
    )


def _record(c: _Carry, when, t, kind, y, mode, margin) -> _Carry:
    """Append an event row when ``when`` holds (a masked write keeps the loop branch-free)."""
    i = jnp.minimum(c.log_count, c.log_time.shape[0] - 1)

    def put(buffer, value):
        return buffer.at[i].set(jnp.where(when, value, buffer[i]))

    return eqx.tree_at(
        lambda k: (k.log_count, k.log_time, k.log_kind, k.log_state, k.log_mode, k.log_margin),
        c,
        (c.log_count + when, put(c.log_time, t), put(c.log_kind, kind), put(c.log_state, y),
         put(c.log_mode, mode), put(c.log_margin, margin)),
    )


def _margin(plan: Plan, segment: cm.Segment, t, speed):
    torque = cm.locked_torque(plan.drivetrain, speed, segment.drum_held)
    return plan.drivetrain.static_capacity(segment.engagement_force(t)) - jnp.abs(torque)


def _scheduled_switches(plan: Plan, segment: cm.Segment, c: _Carry) -> _Carry:
    """At a boundary: record the effects' scheduled events, then re-decide the mode."""
    for effect in plan.effects:
        for kind, happens in effect.boundary_events(c.t):
            code = cm.EVENT_KINDS.index(kind)
            c = _record(c, c.at_boundary & happens, c.t, code, c.y, c.mode,
                        _margin(plan, segment, c.t, c.y[cm.MOTOR_SPEED]))
    decided, decided_y = decide_at_boundary(plan, segment, c.t, c.y)
    new_mode = jnp.where(c.at_boundary, decided, c.mode)
    c = eqx.tree_at(lambda k: k.y, c, jnp.where(c.at_boundary, decided_y, c.y))
    # The first decision (t = 0) sets the initial mode; it is not an event.
    kind = cm.transition_kind(jnp.where(c.segments == 0, -1, c.mode), new_mode)
    switched = c.at_boundary & (kind != cm.NO_EVENT)
    c = _record(c, switched, c.t, kind, c.y, new_mode, _margin(plan, segment, c.t, c.y[cm.MOTOR_SPEED]))
    return eqx.tree_at(lambda k: (k.mode, k.switches), c, (new_mode, c.switches + switched))


def _apply_event(plan: Plan, segment: cm.Segment, c: _Carry, t, y, mask, hit) -> _Carry:
    """A guard fired at (t, y): lock, reverse or unlock with the matching reset, or an observation."""
    dt = plan.drivetrain
    slip_hit, forward_hit = mask[0], mask[1]
    observed = mask[3] | mask[4]
    valley = mask[cm.SLIP_VALLEY]  # a slip valley above zero: nothing happened, go on
    c = _record(c, observed, t, jnp.where(mask[3], cm.SLIP_PEAK, cm.LOAD_LOWEST), y, c.mode,
                _margin(plan, segment, t, y[cm.MOTOR_SPEED]))
    c = eqx.tree_at(lambda k: k.observations, c, c.observations + (observed | valley))
    hit = hit & ~observed & ~valley
    # Sides that meet move on together: both take the speed that keeps their
    # angular momentum (or stay still when the brake holds the drum).
    common = _common_speed(dt, segment, y)
    met = y.at[cm.MOTOR_SPEED].set(common).at[cm.OUTPUT_SPEED].set(common)
    y = jnp.where(slip_hit, met, y)
    after_meeting = cm.static_check(dt, segment, t, common)
    new_mode = jnp.where(slip_hit, after_meeting,
                         jnp.where(forward_hit, cm.SLIP_FORWARD, cm.SLIP_BACKWARD))
    kind = jnp.where(slip_hit, jnp.where(after_meeting == LOCKED, cm.LOCK, cm.REVERSAL), cm.UNLOCK)
    c = _record(c, hit, t, kind, y, new_mode, _margin(plan, segment, t, y[cm.MOTOR_SPEED]))
    return eqx.tree_at(
        lambda k: (k.y, k.mode, k.switches),
        c,
        (jnp.where(hit, y, c.y), jnp.where(hit, new_mode, c.mode), c.switches + hit),
    )


def _solve_segment(plan: Plan, segment: cm.Segment, c: _Carry, solver):
    observing = c.observations < plan.max_switches
    event = diffrax.Event(
        cond_fn=list(cm.GUARDS),
        root_finder=CrossingBisection(),
        direction=False,
    )
    save_times = jnp.clip(plan.grid, c.t, segment.end)
    return diffrax.diffeqsolve(
        diffrax.ODETerm(cm.vector_field),
        solver,
        t0=c.t,
        t1=segment.end,
        dt0=None,
        y0=c.y,
        args=(plan.drivetrain, segment, c.mode, observing),
        # Two save lists: after an event diffrax writes the final value right after
        # the last grid value it kept, so the end of the solve gets a list of its own.
        saveat=diffrax.SaveAt(subs=[diffrax.SubSaveAt(ts=save_times), diffrax.SubSaveAt(t1=True)]),
        stepsize_controller=diffrax.PIDController(rtol=plan.rtol, atol=plan.atol, dtmax=c.step_cap),
        event=event,
        max_steps=MAX_STEPS_PER_SEGMENT,
        adjoint=diffrax.ForwardMode(),
        throw=False,
    )


def _step(plan: Plan, solver, c: _Carry) -> _Carry:
    segment = segment_from(plan, c.t)
    c = _scheduled_switches(plan, segment, c)
    c = _note(plan, segment, c, c.t, c.y, c.mode)
    start_t, start_y = c.t, c.y
    sol = _solve_segment(plan, segment, c, solver)

    (_, (t_end,)), (grid_values, (y_end,)) = sol.ts, sol.ys
    hit = sol.result == diffrax.RESULTS.event_occurred
    failed = ~(hit | (sol.result == diffrax.RESULTS.successful))
    mask = [jnp.asarray(m) & hit for m in sol.event_mask]
    # A slip valley below zero: the crossing fell inside one step and was missed.
    # Throw this pass away and solve again from its start with steps capped well
    # below the dip's length, so that a step ends inside it.
    s = cm.slip_direction(c.mode)
    missed = mask[cm.SLIP_VALLEY] & (s * (y_end[cm.MOTOR_SPEED] - y_end[cm.OUTPUT_SPEED]) < 0)
    kept = ~missed
    mask = [m & kept for m in mask]
    rows = (plan.grid >= c.t) & (plan.grid < t_end) & kept
    grid_state = jnp.where(rows[:, None], grid_values, c.grid_state)
    grid_mode = jnp.where(rows, c.mode, c.grid_mode)
    slipping = (c.mode == cm.SLIP_FORWARD) | (c.mode == cm.SLIP_BACKWARD)
    y_end = jnp.where(missed, start_y, y_end)
    t_reached = jnp.where(missed, start_t, t_end)
    c = _note(plan, segment, c, t_reached, y_end, c.mode)
    c = eqx.tree_at(
        lambda k: (k.slip_time, k.grid_state, k.grid_mode, k.steps, k.rejected, k.segments),
        c,
        (c.slip_time + jnp.where(slipping & ~failed & kept, t_end - c.t, 0.0), grid_state, grid_mode,
         c.steps + sol.stats["num_steps"], c.rejected + sol.stats["num_rejected_steps"], c.segments + 1),
    )
    c = _apply_event(plan, segment, eqx.tree_at(lambda k: k.y, c, y_end), t_end, y_end, mask, hit & kept)
    c = _note(plan, segment, c, t_reached, c.y, c.mode)
    status = jnp.where(failed, SOLVER_FAILED,
                       jnp.where(c.switches > plan.max_switches, CHATTERING, c.status))
    return eqx.tree_at(
        lambda k: (k.t, k.at_boundary, k.status, k.step_cap),
        c,
        (t_reached, kept & (~hit | (t_end >= segment.end)), status,
         jnp.where(missed, (t_end - start_t) / 8.0, jnp.inf)),
    )


def _run(plan: Plan, solver, max_segments: int, log_size: int) -> RawRun:
    global trace_count
    trace_count += 1
    rows = plan.grid.shape[0]
    nan = jnp.nan
    c = _Carry(
        t=jnp.zeros(()),
        y=plan.initial_state,
        mode=jnp.array(OPEN),
        at_boundary=jnp.array(True),
        status=jnp.array(OK),
        switches=jnp.array(0),
        segments=jnp.array(0),
        steps=jnp.array(0),
        rejected=jnp.array(0),
        grid_state=jnp.full((rows, cm.STATE_SIZE), nan),
        grid_mode=jnp.full((rows,), -1),
        log_count=jnp.array(0),
        log_time=jnp.full((log_size,), nan),
        log_kind=jnp.full((log_size,), cm.NO_EVENT),
        log_state=jnp.full((log_size, cm.STATE_SIZE), nan),
        log_mode=jnp.full((log_size,), -1),
        log_margin=jnp.full((log_size,), nan),
        observations=jnp.array(0),
        step_cap=jnp.full((), jnp.inf),
        peak_torque=jnp.zeros(()),
        peak_slip=jnp.zeros(()),
        lowest_position=jnp.zeros(()),
        slip_time=jnp.zeros(()),
        lockup_time=jnp.full((), nan),
    )

    def going(c: _Carry):
        return (c.t < plan.duration) & (c.status == OK) & (c.segments < max_segments)

    c = jax.lax.while_loop(going, functools.partial(_step, plan, solver), c)
    status = jnp.where((c.status == OK) & (c.t < plan.duration), TOO_MANY_SEGMENTS, c.status)
    # The end of the run: rows at the duration (and the grid's padding) take the final state.
    last = plan.grid >= c.t
    grid_state = jnp.where(last[:, None] & (status == OK), c.y, c.grid_state)
    grid_mode = jnp.where(last & (status == OK), c.mode, c.grid_mode)
    return RawRun(
        grid_state=grid_state,
        grid_mode=grid_mode,
        grid_outputs=row_outputs(plan, plan.grid, grid_state, grid_mode),
        event_outputs=row_outputs(plan, c.log_time, c.log_state, c.log_mode),
        event_time=c.log_time,
        event_kind=c.log_kind,
        event_state=c.log_state,
        event_mode=c.log_mode,
        event_margin=c.log_margin,
        event_count=c.log_count,
        final_state=c.y,
        extremes={
            "lockup_time": c.lockup_time,
            "slip_duration": c.slip_time,
            "peak_clutch_torque": c.peak_torque,
            "peak_slip_speed": c.peak_slip,
            "lowest_load_position": c.lowest_position,
        },
        switch_count=c.switches,
        status=status,
        end_time=c.t,
        steps=c.steps,
        rejected_steps=c.rejected,
        segments=c.segments,
    )


@functools.lru_cache(maxsize=None)
def compiled_run(solver_name: str, max_segments: int, log_size: int):
    """The jitted loop for a solver and buffer sizes; shapes of the plan select the rest."""
    solver = SOLVERS[solver_name]()
    return jax.jit(functools.partial(_run, solver=solver, max_segments=max_segments, log_size=log_size))

"""Closed-form reference solution of the two-shaft hoist model.

Between scheduled boundaries (force-table times, brake release) the engagement
force is linear in time, and in every clutch mode the equations are linear with
constant coefficients: the motor side is a first-order lag driven by a linear
torque, the output side a polynomial.  Every state and every integral (load
position, clutch energy, motor work) is therefore a short sum of terms
``coef * u**k * exp(-mu*u)`` in the local time ``u``.  Mode switches inside a
segment are the first roots of such sums, refined to machine precision, so the
result is a reference for the numerical hybrid solver, not another
approximation of it.

Covers the canonical scene and what reduces to it: a linear motor, the cone
clutch with a piecewise-linear engagement force, the gear pair, the drum, a
rigid hanging load, the holding brake and a flywheel on either shaft (through
:mod:`hoistsim.references.model`'s own reduction, not the elements').  Other motor
characteristics are checked against independent answers of their own
(``tests/machine/test_elements.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .exppoly import ExpPoly as ExpPoly
from .exppoly import first_crossing as first_crossing
from .model import (
    LOCKED,
    OPEN,
    SLIP_BACKWARD,
    SLIP_FORWARD,
    SLIP_RESOLUTION,
    STICK_TOLERANCE,
    Drivetrain,
    ForceSchedule,
    Machine,
    force_at,
    initial_speeds,
)

KEYS = ("motor_speed", "output_speed", "load_position", "clutch_energy", "motor_work")


@dataclass(frozen=True)
class ExactEvent:
    time: float
    kind: str  # "lock", "unlock", "reversal", "brake_release", "engage", "disengage"
    mode: int  # mode after the event


@dataclass
class _Piece:
    """One stretch of constant mode: closed forms in u = t - start."""

    start: float
    end: float
    mode: int
    motor: ExpPoly
    output: ExpPoly
    load_rate: ExpPoly  # dx/du
    slip_power: ExpPoly  # T_k * |wa - wb|
    motor_power: ExpPoly  # C(wa) * wa
    origin: tuple  # (x, E, Wm) at u = 0
    guards: tuple  # ((guard, mode after it fires, kind), ...)

    def values(self, u):
        x0, energy0, work0 = self.origin
        return (self.motor(u), self.output(u), x0 + self.load_rate.integral(u),
                energy0 + self.slip_power.integral(u), work0 + self.motor_power.integral(u))


class _Hoist:
    """The drivetrain as plain floats, with the closed forms of each mode."""

    def __init__(self, drivetrain: Drivetrain):
        d = drivetrain
        self.Ja, self.Jb = float(d.motor_inertia), float(d.output_inertia)
        self.C0, self.w0 = float(d.stall_torque), float(d.no_load_speed)
        self.TL, self.c = float(d.load_torque), float(d.clutch_constant)
        self.fs, self.fk = float(d.static_friction), float(d.kinetic_friction)
        self.rope = float(d.rope_radius) / float(d.ratio)  # load speed per output speed
        self.beta = self.C0 / self.w0  # motor torque lost per rad/s

    def motor_torque(self, w):
        return self.C0 - self.beta * w

    def locked_torque(self, w, held):
        """Torque the clutch must carry to keep both shafts together."""
        if held:
            return self.motor_torque(w)  # the drum does not move; the motor pushes on it
        # (J_b C + J_a T_L) / (J_a + J_b): each side's torque weighted by the other's inertia
        share = self.Jb / (self.Ja + self.Jb)
        return share * self.motor_torque(w) + (1.0 - share) * self.TL

    def lag(self, inertia, a, b, w_init):
        """Solution of inertia * w' = a + b u - beta * w with w(0) = w_init."""
        p1 = b / self.beta
        p0 = (a - inertia * p1) / self.beta
        return ExpPoly.poly(p0, p1) + ExpPoly.exp(w_init - p0, self.beta / inertia)

    def piece(self, mode, start, force, slope, wa, wb, held, origin):
        """Closed forms from (wa, wb) at ``start``; force(u) = force + slope*u."""
        if mode == LOCKED:
            if held:  # locked to a held drum: both shafts are at rest
                motor = output = ExpPoly.poly(0.0)
            else:
                motor = output = self.lag(self.Ja + self.Jb, self.C0 - self.TL, 0.0, wa)
            torque = self.locked_torque(motor, held)
            hold = self.fs * self.c * (1.0 + STICK_TOLERANCE)  # a clutch at its limit holds
            capacity = ExpPoly.poly(hold * force, hold * slope)
            guards = ((capacity - torque, SLIP_FORWARD, "unlock"),
                      (capacity + torque, SLIP_BACKWARD, "unlock"))
            slip_power = ExpPoly()
        else:
            s = {SLIP_FORWARD: 1.0, SLIP_BACKWARD: -1.0, OPEN: 0.0}[mode]
            k0, k1 = s * self.fk * self.c * force, s * self.fk * self.c * slope  # s T_k(u)
            motor = self.lag(self.Ja, self.C0 - k0, -k1, wa)
            if held:
                output = ExpPoly.poly(wb)
            else:  # J_b wb' = s T_k(u) - T_L integrates to a quadratic
                output = ExpPoly.poly(wb, (k0 - self.TL) / self.Jb, k1 / (2.0 * self.Jb))
            slip_power = ExpPoly.poly(k0, k1) * (motor - output)  # s T_k (wa - wb) >= 0
            guards = () if mode == OPEN else ((s * (motor - output), None, "slip_zero"),)
        return _Piece(start, start, mode, motor, output, output * self.rope, slip_power,
                      self.motor_torque(motor) * motor, origin, guards)

    def static_mode(self, w, force, held):
        """Mode at zero slip: locked if the static capacity holds the locked torque."""
        torque = self.locked_torque(w, held)
        if abs(torque) <= self.fs * self.c * force * (1.0 + STICK_TOLERANCE):
            return LOCKED
        return SLIP_FORWARD if torque > 0.0 else SLIP_BACKWARD

    def decide(self, wa, wb, force_start, force_end, held):
        """Mode at a scheduled boundary, from the coming segment's force and brake, and the speeds then.

        A slip within SLIP_RESOLUTION of the no-load speed is no slip: the sides
        are merged (momentum kept) if the clutch holds.
        """
        if force_start == 0.0 and force_end == 0.0:
            return OPEN, wa, wb
        if abs(wa - wb) > SLIP_RESOLUTION * self.w0:  # after a lock both speeds are the same float
            return (SLIP_FORWARD if wa > wb else SLIP_BACKWARD), wa, wb
        common = 0.0 if held else (self.Ja * wa + self.Jb * wb) / (self.Ja + self.Jb)
        mode = self.static_mode(common, force_start, held)
        return (mode, common, common) if mode == LOCKED else (mode, wa, wb)


def _segment_force(times, forces, a, b):
    """Value at a (right-continuous) and slope of the table on (a, b), which holds no knot."""
    j = int(np.searchsorted(times, 0.5 * (a + b), side="right")) - 1
    slope = 0.0
    if 0 <= j < times.size - 1:
        slope = float((forces[j + 1] - forces[j]) / (times[j + 1] - times[j]))
    return float(force_at(times, forces, a, np)), slope


def _transition_kind(previous, new):
    if new == LOCKED:
        return "lock"
    if new == OPEN:
        return "disengage"
    if previous == LOCKED:
        return "unlock"
    if previous == OPEN:
        return "engage"
    return "reversal"


class ExactSolution:
    """Piecewise closed-form trajectory; evaluate() is right-continuous at switches."""

    def __init__(self, pieces, events, final, duration, initial_mode):
        self._pieces = pieces
        self._starts = np.array([p.start for p in pieces])
        self.events = events
        self.final = final
        self.duration = duration
        self.slip_energy = final["clutch_energy"]
        locks = [e.time for e in events if e.mode == LOCKED]
        self.lockup_time = 0.0 if initial_mode == LOCKED else (locks[0] if locks else math.nan)

    def slip_power(self, t):
        """The clutch's heat of slip (W) at times t, right-continuous at switches."""
        flat = np.atleast_1d(np.asarray(t, dtype=float))
        index = np.clip(np.searchsorted(self._starts, flat, side="right") - 1, 0, None)
        return np.asarray([self._pieces[i].slip_power(u - self._pieces[i].start) for i, u in zip(index, flat)])

    def evaluate(self, t):
        t = np.asarray(t, dtype=float)
        flat = np.atleast_1d(t).ravel()
        slack = 1e-12 * max(1.0, self.duration)
        if np.any(flat < -slack) or np.any(flat > self.duration + slack):
            raise ValueError("times must lie in [0, duration]")
        flat = np.clip(flat, 0.0, self.duration)
        out = {key: np.empty(flat.shape) for key in KEYS}
        out["mode"] = np.empty(flat.shape, dtype=int)
        index = np.clip(np.searchsorted(self._starts, flat, side="right") - 1, 0, None)
        for i in np.unique(index):
            mask = index == i
            piece = self._pieces[i]
            for key, value in zip(KEYS, piece.values(flat[mask] - piece.start)):
                out[key][mask] = value
            out["mode"][mask] = piece.mode
        end = flat >= self.duration  # the state after any event at the very end
        for key in out:
            out[key][end] = self.final[key]
        return {key: value.reshape(t.shape) for key, value in out.items()}


def solve_exact(drivetrain, force_times, force_forces, duration, *, initial_motor_speed=0.0,
                initial_output_speed=0.0, brake_release=None, max_events=10_000) -> ExactSolution:
    hoist = _Hoist(drivetrain)
    times = np.asarray(force_times, dtype=float).ravel()
    forces = np.asarray(force_forces, dtype=float).ravel()
    duration = float(duration)
    if times.size == 0 or times.shape != forces.shape or np.any(np.diff(times) < 0.0):
        raise ValueError("force table needs matching, non-decreasing times and forces")
    if not (np.isfinite(duration) and duration > 0.0):
        raise ValueError("duration must be positive")
    release = None if brake_release is None else max(float(brake_release), 0.0)

    def held_from(t):  # held on the segment that starts at t
        return release is not None and t < release

    wa, wb = float(initial_motor_speed), float(initial_output_speed)
    if held_from(0.0) and wb != 0.0:
        raise ValueError("the output shaft must be at rest while the brake holds it")
    cuts = {0.0, duration} | {float(t) for t in times if 0.0 < t < duration}
    if release is not None and release < duration:
        cuts.add(release)
    cuts = sorted(cuts)

    x = energy = work = 0.0
    mode = initial_mode = None
    pieces, events = [], []

    def record(time, kind, new_mode):
        events.append(ExactEvent(float(time), kind, int(new_mode)))
        if len(events) > max_events:
            raise RuntimeError(f"chattering: more than {max_events} events by t = {time!r} s")

    for a, b in zip(cuts[:-1], cuts[1:]):
        force0, slope = _segment_force(times, forces, a, b)
        held = held_from(a)
        new_mode, wa, wb = hoist.decide(wa, wb, force0, force0 + slope * (b - a), held)
        if release is not None and a == release:
            record(a, "brake_release", new_mode)
        if mode is None:
            initial_mode = new_mode
        elif new_mode != mode:
            record(a, _transition_kind(mode, new_mode), new_mode)
        mode = new_mode

        t = a
        while True:
            u_force = force0 + slope * (t - a)
            piece = hoist.piece(mode, t, u_force, slope, wa, wb, held, (x, energy, work))
            u_end = b - t
            hit = None
            for guard, after, kind in piece.guards:
                u = first_crossing(guard, u_end)
                if u is not None and (hit is None or u < hit[0]):
                    hit = (u, after, kind)
            u = u_end if hit is None else hit[0]
            t_next = b if u == u_end else t + u
            wa, wb, x, energy, work = (float(v) for v in piece.values(u))
            piece.end = t_next
            if t_next > t:
                pieces.append(piece)
            t = t_next
            if hit is None:
                break
            _, after, kind = hit
            if kind == "slip_zero":
                # Slip closes: both shafts take the common speed that conserves momentum.
                w = 0.0 if held else (hoist.Ja * wa + hoist.Jb * wb) / (hoist.Ja + hoist.Jb)
                wa = wb = w
                after = hoist.static_mode(w, force0 + slope * (t - a), held)
                kind = "lock" if after == LOCKED else "reversal"
            else:
                wb = wa  # unlock starts from exactly zero slip
            mode = after
            record(t, kind, mode)

    final = dict(zip(KEYS, (wa, wb, x, energy, work)))
    final["mode"] = int(mode)
    return ExactSolution(pieces, events, final, duration, initial_mode)


def exact_from_scenario(scenario) -> ExactSolution:
    holding_brake_only(scenario)
    drivetrain = Machine.from_scenario(scenario).reduced()
    schedule = ForceSchedule.from_scenario(scenario)
    brake = getattr(scenario, "brake", None)
    motor_speed, output_speed = initial_speeds(scenario, drivetrain)
    return solve_exact(
        drivetrain, schedule.times, schedule.forces, scenario.simulation.duration,
        initial_motor_speed=motor_speed,
        initial_output_speed=output_speed,
        brake_release=brake.release_time if brake else None,
    )


def clutch_torque(drivetrain, mode, force, motor_speed, held):
    """Torque through the clutch (N*m) in the closed form's terms, at rows of (mode, force, motor speed, held).

    Locked: what the motor torque does not spend on the motor's own inertia
    ((J_b C + J_a T_L)/(J_a + J_b), or C itself while the brake holds the drum);
    slipping: the kinetic torque in the slip's direction; open: 0.
    """
    hoist = _Hoist(drivetrain)
    mode, force = np.asarray(mode), np.asarray(force, float)
    motor_speed, held = np.asarray(motor_speed, float), np.asarray(held, bool)
    locked = np.where(held, hoist.motor_torque(motor_speed), hoist.locked_torque(motor_speed, False))
    kinetic = hoist.fk * hoist.c * force
    return np.where(mode == LOCKED, locked, np.where(mode == SLIP_FORWARD, kinetic,
                                                     np.where(mode == SLIP_BACKWARD, -kinetic, 0.0)))


def holding_brake_only(scenario) -> None:
    """A ValueError where the closed form (and :mod:`.scipy_reference`, which solves its equations) does not
    cover the scenario.  It knows the holding brake (the drum held, then free), the ideal mesh and constant
    friction, not a brake that slips, a pawl, a lossy mesh or friction that fades with temperature (the
    clutch's temperature itself changes nothing it solves)."""
    brake = getattr(scenario, "brake", None)
    if brake is not None and brake.static_torque is not None:
        raise ValueError("the closed form covers a holding brake only, not one with static_torque")
    if getattr(scenario, "ratchet", None) is not None:
        raise ValueError("the closed form does not cover a ratchet")
    if scenario.gears.characteristic != "ideal":
        raise ValueError("the closed form covers the ideal mesh only, not gears.efficiency")
    heating = getattr(scenario, "clutch_heating", None)
    if heating is not None and heating.fades:
        raise ValueError("the closed form covers constant friction only, not clutch_heating's friction tables")

"""A hand-compiled peer of hoistsim for the exercise-6 hoist: a Numba event-restart integrator on one core.

The reduced model (two shafts meeting at the cone clutch): side a the motor (J_a), side b the clutch
output with the drum and load reduced to it (pinion, wheel and clutch halves without inertia, as in
the scenes), J_b = (I + M R^2) / tau^2, load torque T_L = M g R / tau, motor torque C(w) = C0 (1 - w / w0), static
capacity f_a c F and kinetic torque f c F with c = n r_m / sin(beta), r_m = (r_i + r_e) / 2 (uniform
wear, hoistsim's default).  States: motor_speed, output_speed (the pinion's; the drum turns 1/tau as
fast) and the clutch's slip energy.

Dormand-Prince 5(4) with adaptive steps (error norm RMS of err / (atol + rtol max(|y0|, |y1|)),
I control: safety 0.9, factor clipped to 0.2..10, Hairer's initial step at every restart).  Events
(slip reaching zero while slipping; the locked clutch's torque reaching its capacity) are located
on DP5's continuous extension by the Illinois method to 1e-14 s, and the integration restarts
there in the new mode.  Scheduled changes (force steps, the brake's release) are segment
boundaries: integrated up to exactly, then the modes are decided by the static check.

The engagement force is constant in each segment (a step table); while the holding brake holds,
side b is still and the clutch must be open.  One core, runs one after another; ``parallel=True``
spreads the runs over every core (Numba's ``prange``, each run as it is on one core).

    python benchmarks/numba_peer.py      # a few runs of both scenes, printed
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from numba import njit, prange

LOCKED, SLIP_FORWARD, SLIP_BACKWARD, OPEN = 0, 1, 2, 3  # hoistsim's clutch_mode numbers

Machine = namedtuple("Machine", "motor_inertia output_inertia stall_torque no_load_speed load_torque "
                                "clutch_constant static_friction kinetic_friction gear_ratio")


def exercise6_machine(motor_inertia=0.9, load_mass=500.0, drum_inertia=40.0, drum_diameter=0.40,
                      pinion_teeth=17, wheel_teeth=90, stall_torque=500.0, no_load_rpm=300.0,
                      inner_radius=0.20, outer_radius=0.24, half_angle_deg=25.0, surfaces=1,
                      static_friction=0.3, kinetic_friction=0.1, gravity=9.81) -> Machine:
    """The exercise-6 hoist reduced to the two clutch shafts (SI units)."""
    tau = wheel_teeth / pinion_teeth
    rope_radius = 0.5 * drum_diameter
    mean_radius = 0.5 * (inner_radius + outer_radius)  # uniform wear
    return Machine(motor_inertia=motor_inertia,
                   output_inertia=(drum_inertia + load_mass * rope_radius**2) / tau**2,
                   stall_torque=stall_torque, no_load_speed=no_load_rpm * 2.0 * math.pi / 60.0,
                   load_torque=load_mass * gravity * rope_radius / tau,
                   clutch_constant=surfaces * mean_radius / math.sin(math.radians(half_angle_deg)),
                   static_friction=static_friction, kinetic_friction=kinetic_friction, gear_ratio=tau)


@njit
def motor_torque(m, motor_speed):
    return m.stall_torque * (1.0 - motor_speed / m.no_load_speed)


@njit
def locked_clutch_torque(m, speed):
    """The torque a locked clutch carries: T_c = (J_b C + J_a T_L) / (J_a + J_b)."""
    ja, jb = m.motor_inertia, m.output_inertia
    return (jb * motor_torque(m, speed) + ja * m.load_torque) / (ja + jb)


@njit
def rates(m, mode, held, engagement_force, y, k, row):
    """k[row] = d/dt of (motor_speed, output_speed, slip_energy) in ``mode``; side b still while ``held``."""
    ja, jb = m.motor_inertia, m.output_inertia
    drive = motor_torque(m, y[0])
    if mode == LOCKED:
        k[row, 0] = k[row, 1] = (drive - m.load_torque) / (ja + jb)
        k[row, 2] = 0.0
        return
    clutch_torque = 0.0
    if mode == SLIP_FORWARD:
        clutch_torque = m.kinetic_friction * m.clutch_constant * engagement_force
    elif mode == SLIP_BACKWARD:
        clutch_torque = -m.kinetic_friction * m.clutch_constant * engagement_force
    k[row, 0] = (drive - clutch_torque) / ja
    k[row, 1] = 0.0 if held else (clutch_torque - m.load_torque) / jb
    k[row, 2] = clutch_torque * (y[0] - y[1])  # no abs(): smooth through the step where slip ends


@njit
def guard(m, mode, engagement_force, y):
    """Positive while the mode holds, falling through zero at its event (1 where there is none)."""
    if mode == SLIP_FORWARD:
        return y[0] - y[1]
    if mode == SLIP_BACKWARD:
        return y[1] - y[0]
    if mode == LOCKED:
        return m.static_friction * m.clutch_constant * engagement_force - abs(locked_clutch_torque(m, y[0]))
    return 1.0


@njit
def static_mode(m, engagement_force, held, y):
    """The clutch's mode at a restart: open without force, slipping the way the slip goes, and at zero
    slip locked if the locked torque fits the static capacity, else slipping the way it pushes."""
    if engagement_force == 0.0:
        return OPEN
    if held:
        raise ValueError("the peer holds side b only with the clutch open")
    if y[0] != y[1]:
        return SLIP_FORWARD if y[0] > y[1] else SLIP_BACKWARD
    clutch_capacity = m.static_friction * m.clutch_constant * engagement_force
    torque = locked_clutch_torque(m, y[0])
    if abs(torque) <= clutch_capacity:
        return LOCKED
    return SLIP_FORWARD if torque > 0.0 else SLIP_BACKWARD


# Dormand-Prince 5(4): stages (the last row the 5th-order weights: FSAL), error weights (5th - 4th order);
# the nodes 0, 1/5, 3/10, 4/5, 8/9, 1, 1 are not needed (nothing depends on t within a segment)
A = np.array([[0, 0, 0, 0, 0, 0], [1 / 5, 0, 0, 0, 0, 0], [3 / 40, 9 / 40, 0, 0, 0, 0],
              [44 / 45, -56 / 15, 32 / 9, 0, 0, 0],
              [19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0, 0],
              [9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0],
              [35 / 384, 0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84]])
E = np.array([71 / 57600, 0, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40])
# Hairer's continuous extension of DP5 (dense output of order 4)
D = np.array([-12715105075 / 11282082432, 0, 87487479700 / 32700410799, -10690763975 / 1880347072,
              701980252875 / 199316789632, -1453857185 / 822651844, 69997945 / 29380423])


@njit
def step(m, mode, held, force, h, y, k, y_new, rtol, atol):
    """One DP5 step of h from y (k[0]: the rates at y): y_new, k[1..6] (k[6]: the rates at y_new, FSAL),
    and the error norm, RMS of err / (atol + rtol max(|y|, |y_new|))."""
    for s in range(1, 7):
        for i in range(3):
            acc = 0.0
            for j in range(s):
                acc += A[s, j] * k[j, i]
            y_new[i] = y[i] + h * acc
        rates(m, mode, held, force, y_new, k, s)  # the last stage is the 5th-order solution
    total = 0.0
    for i in range(3):
        err = 0.0
        for j in range(7):
            err += E[j] * k[j, i]
        total += (h * err / (atol + rtol * max(abs(y[i]), abs(y_new[i])))) ** 2
    return math.sqrt(total / 3.0)


@njit
def dense(theta, h, y0, y1, k, out):
    """DP5's continuous extension at t0 + theta h."""
    for i in range(3):
        dy = y1[i] - y0[i]
        r3 = h * k[0, i] - dy
        r4 = dy - h * k[6, i] - r3
        r5 = 0.0
        for j in range(7):
            r5 += D[j] * k[j, i]
        out[i] = y0[i] + theta * (dy + (1.0 - theta) * (r3 + theta * (r4 + (1.0 - theta) * h * r5)))


@njit
def locate(m, mode, force, h, y0, y1, k, g0, g1, out):
    """theta in (0, 1] where the guard falls through zero (Illinois, to 1e-14 s); out = y there."""
    lo, hi, side = 0.0, 1.0, 0
    for _ in range(200):
        if (hi - lo) * h <= 1e-14:
            break
        theta = (lo * g1 - hi * g0) / (g1 - g0)
        if not lo < theta < hi:
            theta = 0.5 * (lo + hi)
        dense(theta, h, y0, y1, k, out)
        g = guard(m, mode, force, out)
        if g > 0.0:
            lo, g0 = theta, g
            if side == 1:
                g1 *= 0.5
            side = 1
        else:
            hi, g1 = theta, g
            if side == -1:
                g0 *= 0.5
            side = -1
    dense(hi, h, y0, y1, k, out)  # the side where the event has happened
    return hi


@njit
def initial_step(m, mode, held, force, y, k, y1, rtol, atol):
    """Hairer's starting step (solve_ivp's select_initial_step) from the rates k[0] at y; y1 and k[6]
    are scratch."""
    d0 = d1 = 0.0
    for i in range(3):
        scale = atol + rtol * abs(y[i])
        d0 += (y[i] / scale) ** 2
        d1 += (k[0, i] / scale) ** 2
    d0, d1 = math.sqrt(d0 / 3.0), math.sqrt(d1 / 3.0)
    h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1
    for i in range(3):
        y1[i] = y[i] + h0 * k[0, i]
    rates(m, mode, held, force, y1, k, 6)
    d2 = 0.0
    for i in range(3):
        d2 += ((k[6, i] - k[0, i]) / (atol + rtol * abs(y[i]))) ** 2
    d2 = math.sqrt(d2 / 3.0) / h0
    h1 = max(1e-6, h0 * 1e-3) if max(d1, d2) <= 1e-15 else (0.01 / max(d1, d2)) ** 0.2
    return min(100.0 * h0, h1)


@njit
def solve_run(m, boundaries, forces, held, rtol, atol):
    """One run from rest: segment s spans boundaries[s]..boundaries[s + 1] at force forces[s], side b
    held where held[s].  Returns (lock-up time, locks, motor_speed, drum_speed, slip_energy, steps, rejected)."""
    y, y_new, y_event = np.zeros(3), np.empty(3), np.empty(3)
    k = np.empty((7, 3))
    lockup_time, locks, steps, rejected = np.nan, 0, 0, 0
    t = boundaries[0]
    for seg in range(forces.shape[0]):
        t_end, force, hold = boundaries[seg + 1], forces[seg], held[seg]
        mode = static_mode(m, force, hold, y)
        if mode == LOCKED and math.isnan(lockup_time):
            lockup_time = t
        while t < t_end:  # one pass: from a restart to the segment's end or the next event
            rates(m, mode, hold, force, y, k, 0)
            h = initial_step(m, mode, hold, force, y, k, y_new, rtol, atol)
            g0 = guard(m, mode, force, y)
            event = False
            while t < t_end and not event:
                last = t + h >= t_end * (1.0 - 1e-15)
                if last:
                    h = t_end - t
                err = step(m, mode, hold, force, h, y, k, y_new, rtol, atol)
                if err > 1.0:
                    rejected += 1
                    h *= max(0.2, 0.9 * err ** -0.2)
                    continue
                steps += 1
                g1 = guard(m, mode, force, y_new)
                if g1 < 0.0:  # the mode ends inside this step: restart there
                    theta = locate(m, mode, force, h, y, y_new, k, g0, g1, y_event)
                    t = t_end if last and theta == 1.0 else t + theta * h
                    y[:] = y_event
                    if mode == LOCKED:  # the torque outgrew the capacity: slip the way it pushes
                        mode = SLIP_FORWARD if locked_clutch_torque(m, y[0]) > 0.0 else SLIP_BACKWARD
                    else:  # slip reached zero: the sides meet, momentum kept, then the static check
                        ja, jb = m.motor_inertia, m.output_inertia
                        y[0] = y[1] = (ja * y[0] + jb * y[1]) / (ja + jb)
                        mode = static_mode(m, force, hold, y)
                        if mode == LOCKED:
                            locks += 1
                            if math.isnan(lockup_time):
                                lockup_time = t
                    event = True
                    continue
                t = t_end if last else t + h
                y[:] = y_new
                k[0, :] = k[6]
                g0 = g1
                h *= 10.0 if err == 0.0 else min(10.0, max(0.2, 0.9 * err ** -0.2))
    return lockup_time, locks, y[0], y[1] / m.gear_ratio, y[2], steps, rejected


def _solve_sweep(engagement_forces, m, boundaries, pressed, held, rtol, atol):
    """Every engagement force a run: the force is F where ``pressed``, 0 elsewhere."""
    n = engagement_forces.shape[0]
    lockup_time, final_motor_speed, final_drum_speed = np.empty(n), np.empty(n), np.empty(n)
    slip_energy = np.empty(n)
    locks, steps, rejected = np.empty(n, np.int64), np.empty(n, np.int64), np.empty(n, np.int64)
    for r in prange(n):  # a plain loop where not compiled parallel
        forces = np.where(pressed, engagement_forces[r], 0.0)
        (lockup_time[r], locks[r], final_motor_speed[r], final_drum_speed[r], slip_energy[r], steps[r],
         rejected[r]) = solve_run(m, boundaries, forces, held, rtol, atol)
    return lockup_time, locks, final_motor_speed, final_drum_speed, slip_energy, steps, rejected


solve_sweep = njit(_solve_sweep)
solve_sweep_parallel = njit(parallel=True)(_solve_sweep)


def stepped(engage_time=0.35, duration=2.0):
    """Scene 1: motor run up unloaded, side b held; at engage_time the force steps on and the brake lets go."""
    return np.array([0.0, engage_time, duration]), np.array([False, True]), np.array([True, False])


def direct_start(duration=3.0):
    """Scene 2: everything at rest, the clutch pressed from t = 0."""
    return np.array([0.0, duration]), np.array([True]), np.array([False])


def sweep(engagement_forces, machine, scene, rtol=1e-8, atol=1e-10, parallel=False) -> dict:
    """The runs of ``scene`` (stepped() or direct_start()) at each force: arrays by name (``parallel``:
    spread over every core)."""
    boundaries, pressed, held = scene
    names = ("lockup_time", "lock_events", "final_motor_speed", "final_drum_speed", "slip_energy",
             "steps", "rejected_steps")
    solve = solve_sweep_parallel if parallel else solve_sweep
    values = solve(np.asarray(engagement_forces, float), machine, boundaries, pressed, held, rtol, atol)
    return dict(zip(names, values))


if __name__ == "__main__":
    for label, machine, scene, forces in (
            ("stepped", exercise6_machine(), stepped(), [3800.0, 5000.0, 12000.0]),
            ("direct start", exercise6_machine(motor_inertia=40 * 0.15**2), direct_start(), [2000.0, 3201.0])):
        out = sweep(forces, machine, scene)
        for i, f in enumerate(forces):
            print(label, f, {name: values[i] for name, values in out.items()})

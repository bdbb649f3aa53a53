"""The same hybrid model on scipy's solve_ivp, with event location and explicit restarts.

A straightforward, independent implementation: the peer that the sweep
benchmark and the work-precision study measure hoistsim against, and a second
opinion on the closed-form solution in the tests.  Plain Python per run.

It writes the two-shaft equations out for itself, from :mod:`hoistsim.references.model`'s
reduction, and shares nothing with the elements or the core: an oracle that
used the elements would agree with them by construction.  It covers the scenes
the closed form covers (linear motor, cone clutch, gears, drum, rigid load,
holding brake, flywheel).
"""

from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from .model import LOCKED, OPEN, SLIP_BACKWARD, SLIP_FORWARD, ForceSchedule, Machine, force_at, initial_speeds


def solve_with_scipy(d, times, forces, duration, wa0=0.0, wb0=0.0, release=None, *, method="DOP853",
                     rtol=1e-12, atol=1e-12, max_step=np.inf, dense=True):
    """Integrate the hybrid model with solve_ivp; returns (events, evaluate, pieces, stats).

    ``events`` is a list of (time, kind); ``evaluate(ts)`` gives the state rows
    (motor speed, pinion speed, load position, clutch energy, motor work) at ts
    when ``dense``; ``pieces`` are (start, end, dense output, mode); ``stats`` counts
    steps and right-hand-side evaluations over all restarts.
    """
    Ja, Jb, C0, w0, TL = d.motor_inertia, d.output_inertia, d.stall_torque, d.no_load_speed, d.load_torque
    times, forces = np.asarray(times, float), np.asarray(forces, float)
    cuts = {0.0, duration} | {float(t) for t in times if 0.0 < t < duration}
    if release is not None and 0.0 < release < duration:
        cuts.add(float(release))
    cuts = sorted(cuts)

    def locked_torque(w, held):
        C = C0 * (1.0 - w / w0)
        alpha = 0.0 if held else (C - TL) / (Ja + Jb)
        return C - Ja * alpha

    def static(w, F, held):
        Tc = locked_torque(w, held)
        if abs(Tc) <= d.static_friction * d.clutch_constant * F:
            return LOCKED
        return SLIP_FORWARD if Tc > 0 else SLIP_BACKWARD

    y = np.array([wa0, wb0, 0.0, 0.0, 0.0])
    mode, events, pieces, stats = None, [], [], {"steps": 0, "evaluations": 0}
    for a, b in zip(cuts[:-1], cuts[1:]):
        mid = 0.5 * (a + b)
        fa, fm = float(force_at(times, forces, a, np)), float(force_at(times, forces, mid, np))

        def force(t, a=a, fa=fa, fm=fm, mid=mid):  # linear on the segment; no step inside
            return fa + (fm - fa) * (t - a) / (mid - a)

        held = release is not None and a < release
        if fa == 0.0 and fm == 0.0:
            new = OPEN
        elif y[0] != y[1]:
            new = SLIP_FORWARD if y[0] > y[1] else SLIP_BACKWARD
        else:
            new = static(y[0], fa, held)
        if release is not None and a == max(release, 0.0):
            events.append((a, "brake_release"))
        if mode is not None and new != mode:
            kind = ("lock" if new == LOCKED else "disengage" if new == OPEN else
                    "unlock" if mode == LOCKED else "engage" if mode == OPEN else "reversal")
            events.append((a, kind))
        mode = new
        t = a
        while t < b:
            def rhs(t, y, mode=mode, held=held):
                wa, wb = y[0], y[1]
                C = C0 * (1.0 - wa / w0)
                if mode == LOCKED:
                    acc = 0.0 if held else (C - TL) / (Ja + Jb)
                    return [acc, acc, d.rope_radius / d.ratio * wb, 0.0, C * wa]
                s = {SLIP_FORWARD: 1.0, SLIP_BACKWARD: -1.0, OPEN: 0.0}[mode]
                Tk = d.kinetic_friction * d.clutch_constant * force(t)
                return [(C - s * Tk) / Ja, 0.0 if held else (s * Tk - TL) / Jb,
                        d.rope_radius / d.ratio * wb, s * Tk * (wa - wb), C * wa]

            if mode == LOCKED:
                def cap_fwd(t, y, held=held):
                    return d.static_friction * d.clutch_constant * force(t) - locked_torque(y[0], held)

                def cap_bwd(t, y, held=held):
                    return d.static_friction * d.clutch_constant * force(t) + locked_torque(y[0], held)
                guards = [cap_fwd, cap_bwd]
            elif mode == OPEN:
                guards = []
            else:
                s = 1.0 if mode == SLIP_FORWARD else -1.0

                def slip(t, y, s=s):
                    return s * (y[0] - y[1])
                guards = [slip]
            for g in guards:
                g.terminal, g.direction = True, -1
            sol = solve_ivp(rhs, (t, b), y, method=method, rtol=rtol, atol=atol, max_step=max_step,
                            events=guards or None, dense_output=dense)
            stats["evaluations"] += sol.nfev
            stats["steps"] += len(sol.t) - 1
            pieces.append((t, float(sol.t[-1]), sol.sol, mode))
            if sol.status != 1:
                t, y = b, sol.y[:, -1].copy()
                continue
            which = next(i for i, te in enumerate(sol.t_events) if len(te))
            t, y = float(sol.t_events[which][0]), sol.y_events[which][0].copy()
            if mode == LOCKED:
                mode = SLIP_FORWARD if which == 0 else SLIP_BACKWARD
                events.append((t, "unlock"))
            else:
                w = 0.0 if held else (Ja * y[0] + Jb * y[1]) / (Ja + Jb)
                y[0] = y[1] = w
                mode = static(w, force(t), held)
                events.append((t, "lock" if mode == LOCKED else "reversal"))

    def evaluate(ts):
        out = np.empty((5, len(ts)))
        for j, tq in enumerate(ts):
            start, end, dense, _ = [p for p in pieces if p[0] <= tq][-1]
            out[:, j] = dense(min(tq, end))
        return out

    return events, evaluate, pieces, stats


def solve_scenario_with_scipy(scenario, method="RK45", rtol=None, atol=None, dense=False):
    """:func:`solve_with_scipy` for a scenario (its tolerances unless given)."""
    from .exact import holding_brake_only

    holding_brake_only(scenario)
    drivetrain = Machine.from_scenario(scenario).reduced()
    schedule = ForceSchedule.from_scenario(scenario)
    wa0, wb0 = initial_speeds(scenario, drivetrain)
    sim = scenario.simulation
    return solve_with_scipy(drivetrain, schedule.times, schedule.forces, sim.duration, wa0, wb0,
                            scenario.brake.release_time if scenario.brake else None, method=method,
                            rtol=rtol or sim.rtol, atol=atol or sim.atol, dense=dense)

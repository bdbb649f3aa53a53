"""Chains of masses on a line: a property over random chains of masses, spring-dampers and a gap.

Three masses in a row, a spring-damper between the first two, an elasto-gap (pushing only) between the second
and the third, a spring-damper from the third to the ground, and a force of an offset and a harmonic on the first:
at every output row every mass is where an independent integration of the same chain puts it (scipy's DOP853 at
rtol 1e-12, the gap written as Modelica writes it: f_c = c s, f_d = d v clamped to [f_c, -f_c] while s < 0), and
the ledger closes.  One structure, one compiled program, for every chain drawn.

Three masses on springs, each on a friction with a Stribeck curve between two stops with a restitution, the first
pushed: every position where an independent piecewise integration of stick, slip, breakaway, impacts, rebounds and
rest puts it (each mass decided on its own: the springs are their only ties), and the ledger closing with the
impacts' losses.  A chain that integration cannot get through (more than a few thousand pieces) is drawn again.
This search found a shared plastic impact booked twice, slips and breakaways whose guards a restart left below zero
(never to fire), and a stop's pull lost within one long step of a machine at rest.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from helpers import property_settings
from hypothesis import given, reject
from hypothesis import strategies as st
from scipy.integrate import solve_ivp

from hoistsim import scenario_from_dict, simulate

SETTINGS = property_settings(12, derandomize=not os.environ.get("HOISTSIM_PROPERTY_SEARCH"))
DURATION = 2.0  # s

masses = st.floats(0.5, 5.0)
stiffnesses = st.floats(10.0, 1000.0)
dampings = st.floats(0.0, 20.0)
lengths = st.floats(-0.5, 0.5)
starts = st.floats(-0.5, 0.5)
speeds = st.floats(-2.0, 2.0)


def _scene(m, positions, velocities, c, d, u, force) -> dict:
    offset, amplitude, frequency = force
    line = {f"m{i + 1}": {"mass": f"{m[i]!r} kg", "position": f"{positions[i]!r} m",
                          "velocity": f"{velocities[i]!r} m/s"} for i in range(3)}
    parts = {"s12": ["m1", "m2", False], "gap23": ["m2", "m3", True], "s3": ["m3", "ground", False]}
    springs = {name: {"between": [a, b], "stiffness": f"{c[i]!r} N/m", "damping": f"{d[i]!r} N*s/m",
                      "unstretched_length": f"{u[i]!r} m", "gap": gap}
               for i, (name, (a, b, gap)) in enumerate(parts.items())}
    force1 = {"offset": f"{offset!r} N",
              "harmonics": [{"amplitude": f"{amplitude!r} N", "frequency": f"{frequency!r} Hz"}]}
    return {"name": "line-chain", "drivetrain": {"masses": line, "springs": springs,
                                                 "forces": [{"mass": "m1", "force": force1}]},
            "simulation": {"duration": f"{DURATION} s", "output_interval": "2 ms", "rtol": 1e-11, "atol": 1e-13}}


def _independent(m, positions, velocities, c, d, u, force, times):
    """The chain's positions at ``times``: Newton's law for each mass, the forces written out (not the code's)."""
    offset, amplitude, frequency = force
    m = np.asarray(m)

    def gap_force(s, v):  # Modelica's ElastoGap, n = 1: pushing only while s < 0
        if s >= 0.0:
            return 0.0
        f_c = c[1] * s
        return f_c + min(max(d[1] * v, f_c), -f_c)

    def rates(t, z):
        x, v = z[:3], z[3:]
        f12 = c[0] * (x[1] - x[0] - u[0]) + d[0] * (v[1] - v[0])  # pulls m1 forwards, m2 back
        f23 = gap_force(x[2] - x[1] - u[1], v[2] - v[1])
        f3 = c[2] * (-x[2] - u[2]) + d[2] * (-v[2])  # from m3 to the ground
        push = offset + amplitude * math.sin(2 * math.pi * frequency * t)
        accel = np.array([f12 + push, -f12 + f23, -f23 + f3]) / m
        return np.concatenate([v, accel])

    solved = solve_ivp(rates, (0.0, DURATION), np.concatenate([positions, velocities]), method="DOP853",
                       t_eval=times, rtol=1e-12, atol=1e-14, max_step=1e-3)
    return solved.y[:3]


@SETTINGS
@given(st.tuples(masses, masses, masses), st.tuples(starts, starts, starts), st.tuples(speeds, speeds, speeds),
       st.tuples(stiffnesses, stiffnesses, stiffnesses), st.tuples(dampings, dampings, dampings),
       st.tuples(lengths, lengths, lengths), st.tuples(st.floats(-5.0, 5.0), st.floats(0.0, 20.0),
                                                       st.floats(0.1, 5.0)))
def test_every_mass_of_a_random_chain_is_where_newton_puts_it(m, positions, velocities, c, d, u, force):
    run = simulate(scenario_from_dict(_scene(m, positions, velocities, c, d, u, force)))
    expected = _independent(m, positions, velocities, c, d, u, force, run.time)
    for i in range(3):
        ours = run[f"m{i + 1}_position"]
        scale = max(float(np.ptp(expected[i])), 1e-3)
        np.testing.assert_allclose(ours, expected[i], rtol=0, atol=1e-7 * scale)
    assert run.summary["energy_relative_residual"] < 1e-8


# ------------------------------------------------------------- frictions and stops: stick, slip, impacts, rest

FRICTION_DURATION = 1.5  # s
PIECES = 4000  # the independent integration's pieces at most: a chain that needs more is not drawn again


class _NoProgress(Exception):
    """The independent integration could not get on (a drawn chain it cannot resolve): the example is rejected."""


def _friction_scene(m, starts, velocities, ends, frictions, springs, force) -> dict:
    offset, amplitude, frequency = force
    line = {f"m{i + 1}": {"mass": f"{m[i]!r} kg", "position": f"{starts[i]!r} m",
                          "velocity": f"{velocities[i]!r} m/s"} for i in range(3)}
    stops = {f"ends{i + 1}": {"mass": f"m{i + 1}", "lower": f"{starts[i] - below!r} m",
                              "upper": f"{starts[i] + above!r} m", "restitution": restitution,
                              "rest_speed": "0.01 m/s"}
             for i, (below, above, restitution) in enumerate(ends)}
    bearing = {f"f{i + 1}": {"between": [f"m{i + 1}", "ground"], "force": f"{coulomb!r} N",
                             "stribeck": f"{stribeck!r} N", "decay": f"{decay!r} s/m",
                             "viscous": f"{viscous!r} N*s/m", "peak": peak}
               for i, (coulomb, stribeck, decay, viscous, peak) in enumerate(frictions)}
    ties = {name: {"between": [a, b], "stiffness": f"{c!r} N/m", "damping": f"{d!r} N*s/m",
                   "unstretched_length": f"{u!r} m"}
            for (name, a, b), (c, d, u) in zip((("s12", "m1", "m2"), ("s23", "m2", "m3")), springs)}
    push = {"offset": f"{offset!r} N",
            "harmonics": [{"amplitude": f"{amplitude!r} N", "frequency": f"{frequency!r} Hz"}]}
    return {"name": "line-friction-chain", "drivetrain": {
                "masses": line, "springs": ties, "stops": stops, "bearing_frictions": bearing,
                "forces": [{"mass": "m1", "force": push}]},
            "simulation": {"duration": f"{FRICTION_DURATION} s", "output_interval": "2 ms", "rtol": 1e-11,
                           "atol": 1e-13}}


def _friction_independent(m, starts, velocities, ends, frictions, springs, force, times):
    """The chain's positions at ``times``, integrated piece by piece between its switches, written from the laws.

    The masses touch only through springs, so each is decided on its own: slipping, it feels its friction
    f(w) = coulomb + stribeck exp(-decay w) + viscous w against its velocity; where the velocity reaches zero it
    sticks if the force on it is within peak f(0), else turns round; stuck, it breaks away when the force exceeds
    peak f(0).  Reaching a stop it rebounds at e times its speed, or rests if that is below the rest speed; resting,
    the stop takes any push into it and the friction a pull up to peak f(0).
    """
    offset, amplitude, frequency = force
    m = np.asarray(m)
    lower = np.array([s - e[0] for s, e in zip(starts, ends)])
    upper = np.array([s + e[1] for s, e in zip(starts, ends)])
    restitution = np.array([e[2] for e in ends])
    coulomb, stribeck, decay, viscous, peak = (np.array(column) for column in zip(*frictions))
    breakaway = peak * (coulomb + stribeck)

    def pushes(t, x, v):  # the force on each mass but its friction
        (c12, d12, u12), (c23, d23, u23) = springs
        f12 = c12 * (x[1] - x[0] - u12) + d12 * (v[1] - v[0])
        f23 = c23 * (x[2] - x[1] - u23) + d23 * (v[2] - v[1])
        return np.array([f12 + offset + amplitude * math.sin(2 * math.pi * frequency * t), f23 - f12, -f23])

    def friction(w):
        return coulomb + stribeck * np.exp(-decay * w) + viscous * w

    # each mass: +1 / -1 slipping that way, 0 stuck; pinned: -1 / +1 resting on its lower / upper stop, 0 free
    mode, pinned = np.zeros(3), np.zeros(3)
    x, v = np.array(starts, dtype=float), np.array(velocities, dtype=float)
    v[np.abs(v) < 1e-12] = 0.0  # a speed below any slip's resolution is rest (a subnormal one drawn)
    mode[:] = np.sign(v)

    def settle(t, x, v, i):
        """Mode of mass i at rest: stuck, unless the force on it breaks it away (a stop it rests on takes a push)."""
        f = pushes(t, x, v)[i]
        if abs(f) <= breakaway[i] or np.sign(f) == pinned[i]:
            return 0.0
        pinned[i] = 0.0
        return np.sign(f)

    for i in range(3):
        if mode[i] == 0.0:
            mode[i] = settle(0.0, x, v, i)

    def rates(t, z):
        x, v = z[:3], z[3:]
        accel = np.where(mode != 0.0, (pushes(t, x, v) - mode * friction(np.abs(v))) / m, 0.0)
        return np.concatenate([np.where(mode != 0.0, v, 0.0), accel])

    def watched(i, kind):
        def event(t, z):
            x, v = z[:3], z[3:]
            if kind == "turn":  # slipping: its velocity reaches zero
                return mode[i] * v[i] if mode[i] else 1.0
            if kind == "break":  # stuck: the force on it reaches the breakaway
                f = pushes(t, x, v)[i]
                return (breakaway[i] - abs(f) if pinned[i] == 0.0 else breakaway[i] + pinned[i] * f) \
                    if mode[i] == 0.0 else 1.0
            if kind == "lower":  # sliding down: reaches the lower stop
                return x[i] - lower[i] if mode[i] < 0.0 else 1.0
            return upper[i] - x[i] if mode[i] > 0.0 else 1.0
        event.terminal, event.direction = True, -1
        return event

    events = [watched(i, kind) for i in range(3) for kind in ("turn", "break", "lower", "upper")]
    t, out, z = 0.0, [], np.concatenate([x, v])
    for _piece in range(PIECES):
        if t >= FRICTION_DURATION:
            break
        solved = solve_ivp(rates, (t, FRICTION_DURATION), z, method="DOP853", dense_output=True, events=events,
                           rtol=1e-12, atol=1e-14, max_step=5e-3)
        end = solved.t[-1]
        inside = times[(times >= t) & (times <= end)]
        out.append(solved.sol(inside)[:3] if len(inside) else np.zeros((3, 0)))
        if solved.status == 0:
            break
        fired = [k for k, hits in enumerate(solved.t_events) if len(hits)]
        z = solved.y[:, -1].copy()
        x, v = z[:3], z[3:]
        for k in fired:
            i, kind = divmod(k, 4)
            kind = ("turn", "break", "lower", "upper")[kind]
            if kind == "turn":
                v[i] = 0.0
                mode[i] = settle(end, x, v, i)
            elif kind == "break":
                mode[i] = np.sign(pushes(end, x, v)[i])
                pinned[i] = 0.0
            else:
                x[i] = lower[i] if kind == "lower" else upper[i]
                rebound = -restitution[i] * v[i]
                if abs(rebound) < 0.01:
                    v[i], pinned[i] = 0.0, -1.0 if kind == "lower" else 1.0
                    mode[i] = settle(end, x, v, i)
                else:
                    v[i], mode[i] = rebound, np.sign(rebound)
        for i in np.flatnonzero(mode == 0.0):  # a stop's impact jumps the damper's force on a stuck neighbour
            mode[i] = settle(end, x, v, i)
        t = end
        times = times[times > end]
    else:
        raise _NoProgress
    return np.concatenate(out, axis=1)


frictions = st.tuples(st.floats(0.5, 5.0), st.floats(0.0, 3.0), st.floats(0.0, 5.0), st.floats(0.0, 2.0),
                      st.floats(1.0, 1.5))
ends = st.tuples(st.floats(0.02, 0.3), st.floats(0.02, 0.3), st.floats(0.0, 0.8))
ties = st.tuples(stiffnesses, st.floats(0.0, 5.0), lengths)


@pytest.mark.slow
@SETTINGS
@given(st.tuples(masses, masses, masses), st.tuples(starts, starts, starts),
       st.tuples(*[st.one_of(st.just(0.0), speeds)] * 3), st.tuples(ends, ends, ends),
       st.tuples(frictions, frictions, frictions), st.tuples(ties, ties),
       st.tuples(st.floats(-10.0, 10.0), st.floats(0.0, 40.0), st.floats(0.5, 5.0)))
def test_every_mass_of_a_random_chain_with_frictions_and_stops_is_where_the_laws_put_it(
        m, starts, velocities, ends, frictions, springs, force):
    """Three masses on springs, each on a Stribeck friction between two stops with a restitution, the first pushed:
    every position within 1e-7 of its range of the independent piecewise integration, and the ledger closing with
    the impacts' losses.  One program for every chain."""
    run = simulate(scenario_from_dict(_friction_scene(m, starts, velocities, ends, frictions, springs, force)))
    try:
        expected = _friction_independent(m, starts, velocities, ends, frictions, springs, force, run.time)
    except _NoProgress:
        reject()
    for i in range(3):
        scale = max(float(np.ptp(expected[i])), 1e-3)
        np.testing.assert_allclose(run[f"m{i + 1}_position"], expected[i], rtol=0, atol=1e-7 * scale)
    assert run.summary["energy_relative_residual"] < 1e-8

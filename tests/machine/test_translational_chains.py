"""Chains of masses on a line: a property over random chains of masses, spring-dampers and a gap.

Three masses in a row, a spring-damper between the first two, an elasto-gap (pushing only) between the second
and the third, a spring-damper from the third to the ground, and a force of an offset and a harmonic on the first:
at every output row every mass is where an independent integration of the same chain puts it (scipy's DOP853 at
rtol 1e-12, the gap written as Modelica writes it: f_c = c s, f_d = d v clamped to [f_c, -f_c] while s < 0), and
the ledger closes.  One structure, one compiled program, for every chain drawn.
"""

from __future__ import annotations

import math
import os

import numpy as np
from helpers import property_settings
from hypothesis import given
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

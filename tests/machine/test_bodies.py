"""The bodies' constrained solve on arrays: the masked elimination against a dense solve, a motion held twice, and
locked shafts made to agree to the last bit however their couplings are ordered."""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np
import pytest
from helpers import drawn

from hoistsim.machine.assemble import machine_elements
from hoistsim.machine.core import bodies as bodies_module
from hoistsim.machine.core.bodies import Bodies, solve_response, solve_stuck
from hoistsim.machine.core.layout import Layout

CLUTCH = {"static_friction": 0.3, "kinetic_friction": 0.2, "effective_radius": "1 m", "force": "100 N"}


def _bodies(**parts) -> Bodies:
    return Bodies(Layout(machine_elements(drawn("bodies", **parts))))


def _chain() -> Bodies:
    """J1..J5 and a hub geared to J4 at 3:1, clutched to J5; the clutches of J1..J4 named so that the middle
    one comes last (taken in that order, it joins two groups already made)."""
    shafts = {f"J{i}": {"inertia": f"{i} kg*m^2"} for i in range(1, 6)}
    shafts["hub"] = {"inertia": "0.5 kg*m^2"}
    clutches = {"c12": {"between": ["J1", "J2"], **CLUTCH}, "c34": {"between": ["J3", "J4"], **CLUTCH},
                "c23": {"between": ["J2", "J3"], **CLUTCH}, "c5": {"between": ["hub", "J5"], **CLUTCH},
                "brake": {"between": ["J1", "ground"], **CLUTCH}}
    return _bodies(shafts=shafts, clutches=clutches, gears={"g": {"between": ["J4", "hub"], "ratio": 3}})


@pytest.mark.parametrize("written_out", [False, True], ids=["looped", "written out"])
def test_the_masked_elimination_solves_the_stuck_rows_and_zeroes_the_rest(written_out, monkeypatch):
    # five couplings: their pivots looped, or (as for a few) written out
    monkeypatch.setattr(bodies_module, "UNROLLED", 5 if written_out else 4)
    rng = np.random.default_rng(3)
    g = rng.normal(size=(5, 7))
    matrix = g @ np.diag(1 / rng.uniform(0.5, 2, 7)) @ g.T
    rhs = rng.normal(size=(5, 3))
    stuck = np.array([True, False, True, True, False])
    got = np.asarray(solve_stuck(jnp.asarray(matrix), jnp.asarray(rhs), jnp.asarray(stuck), order=[4, 2, 0, 1, 3]))
    expected = np.zeros_like(rhs)
    expected[stuck] = np.linalg.solve(matrix[np.ix_(stuck, stuck)], rhs[stuck])
    np.testing.assert_allclose(got, expected, rtol=1e-12, atol=1e-12)


def test_a_motion_held_twice_is_carried_by_the_first_in_order():
    bodies = _bodies(shafts={"s": {"inertia": "2 kg*m^2"}},
                     clutches={"one": {"between": ["s", "ground"], **CLUTCH}, "two": {"between": ["s", "ground"], **CLUTCH}})
    held = solve_stuck(bodies.schur(), jnp.asarray([[6.0], [6.0]]), jnp.asarray([True, True]))
    np.testing.assert_allclose(np.asarray(held)[:, 0], [12.0, 0.0], rtol=1e-14)


def test_locked_shafts_agree_to_the_last_bit_whatever_the_couplings_order():
    bodies = _chain()
    values = jnp.asarray([[0.1, 1.0], [0.1 + 3e-17, 2.0], [0.1 - 2e-17, 3.0], [0.1 + 1e-17, 4.0], [0.7, 5.0]])
    # every clutch stuck but the brake: J1..J4 one body, each of its values its first's; J5 the hub's
    aligned = bodies.align(values, jnp.asarray([True, True, True, True, False]))
    assert (np.asarray(aligned[:4]) == np.asarray(aligned[0])).all(), aligned
    np.testing.assert_allclose(np.asarray(bodies.relative(3, aligned)), 0.0, atol=1e-15)
    np.testing.assert_allclose(np.asarray(aligned[4]), np.asarray(aligned[0]) / 3, rtol=1e-15)
    # the brake stuck too: held at zero, J5 with them
    assert (np.asarray(bodies.align(values, jnp.ones(5, bool))) == 0.0).all()
    # the middle one let go: two groups, each of one value
    apart = np.asarray(bodies.align(values, jnp.asarray([True, True, False, False, False])))
    assert (apart[1] == apart[0]).all() and (apart[3] == apart[2]).all() and (apart[0] != apart[2]).any()


def test_the_response_of_locked_shafts_has_equal_rows():
    bodies = _chain()
    layout = bodies.layout
    reply = solve_response(layout, jnp.asarray([True, True, True, False, False]))
    for field in (reply.accel_from_torque, reply.accel_from_sliding):
        rows = np.asarray(field)[:4]
        assert (rows == rows[0]).all()
    # one body's worth of inertia takes any torque on J1..J4: 1 + 2 + 3 + 4 + 0.5 / 9 kg*m^2
    np.testing.assert_allclose(np.asarray(reply.accel_from_torque)[0, :4], 1 / (10 + 0.5 / 9), rtol=1e-14)

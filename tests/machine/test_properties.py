"""Properties over random valid scenes (hypothesis).

- the numerical runs agree with the closed form;
- at every output row a locked clutch carries no more than its static capacity,
  a slipping one exactly its kinetic torque (in the direction of slip), an open
  one nothing;
- when the load can be lifted, more force never delays lock-up and never adds
  clutch heat.
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from helpers import EXERCISE6, engagement_forces, property_settings, reduced
from hypothesis import given
from hypothesis import strategies as st

from hoistsim import exact_from_scenario, scenario_from_dict, simulate
from hoistsim.references.model import STICK_TOLERANCE, Machine

SETTINGS = property_settings(100)


def build(force, mass, motor_rpm, drum_rpm, fs, fk_share, duration="1 s"):
    data = copy.deepcopy(EXERCISE6)
    data["clutch"].update(engagement_force=force, static_friction=fs, kinetic_friction=fs * fk_share)
    data["load"]["mass"] = f"{mass} kg"
    data["initial"] = {"motor_speed": f"{motor_rpm} rpm", "drum_speed": f"{drum_rpm} rpm"}
    data["simulation"].update(duration=duration, output_interval="5 ms")
    return scenario_from_dict(data)


scenes = st.builds(build, engagement_forces, st.floats(0.0, 900.0), st.floats(-50.0, 400.0),
                   st.floats(-30.0, 50.0), st.floats(0.15, 0.4), st.floats(0.0, 1.0))


@SETTINGS
@given(scenes)
def test_random_scenes_agree_with_the_closed_form(s):
    run, exact = simulate(s), exact_from_scenario(s)
    assert list(run.events["kind"]) == [e.kind for e in exact.events]
    np.testing.assert_allclose(run.events["time"], [e.time for e in exact.events], rtol=0, atol=1e-7)
    ref = exact.evaluate(run.time)
    assert np.max(np.abs(run["motor_speed"] - ref["motor_speed"])) < 1e-5
    assert np.max(np.abs(run["drum_speed"] * reduced(run).ratio - ref["output_speed"])) < 1e-5
    assert run.energy_balance["relative_residual"] < 1e-8


@SETTINGS
@given(scenes)
def test_friction_law_holds_at_every_row(s):
    run = simulate(s)
    d = reduced(run)
    torque, force, mode = run["clutch_torque"], run["engagement_force"], run["clutch_mode"]
    locked, forward, backward, open_ = mode == 0, mode == 1, mode == 2, mode == 3
    capacity = d.static_capacity(force) * (1 + STICK_TOLERANCE)
    assert np.all(np.abs(torque[locked]) <= capacity[locked] + 1e-9)
    kinetic = d.kinetic_torque(force)
    np.testing.assert_allclose(torque[forward], kinetic[forward], rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(torque[backward], -kinetic[backward], rtol=1e-12, atol=1e-12)
    assert np.all(torque[open_] == 0.0)
    # and a slipping clutch slips the way its torque says
    assert np.all(run["slip_speed"][forward] >= -1e-9) and np.all(run["slip_speed"][backward] <= 1e-9)


@pytest.mark.slow
@SETTINGS
@given(st.floats(0.0, 800.0), st.floats(100.0, 300.0), st.floats(0.0, 1.0), st.floats(0.0, 1.0))
def test_more_force_never_delays_lockup_nor_adds_heat(mass, motor_rpm, a, b):
    """Engaging at speed on a load at rest, with forces that lift it even while slipping.

    Heat is compared between completed lock-ups: over a horizon in which both
    clutches are still slipping, more force does put more heat in so far.
    """
    probe = build("1000 N", mass, motor_rpm, 0.0, 0.3, 1 / 3)
    d = Machine.from_scenario(probe).reduced()
    lifting = d.load_torque / (d.kinetic_friction * d.clutch_constant)  # kinetic torque = load torque
    low, high = sorted((lifting * (1.02 + 2 * a), lifting * (1.02 + 2 * b)))
    weak = simulate(build(f"{low} N", mass, motor_rpm, 0.0, 0.3, 1 / 3, duration="3 s"))
    strong = simulate(build(f"{high} N", mass, motor_rpm, 0.0, 0.3, 1 / 3, duration="3 s"))
    if math.isnan(weak.lockup_time):
        return  # the weak clutch is still slipping at the end: its heat so far compares with nothing
    assert strong.lockup_time <= weak.lockup_time + 1e-9  # (so the strong one locks too)
    assert strong.slip_energy <= weak.slip_energy * (1 + 1e-9) + 1e-9

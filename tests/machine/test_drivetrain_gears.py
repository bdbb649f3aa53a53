"""Lossy gear stages drawn in series: the motion and the tooth loads in closed form.

Three shafts a -> b -> c geared by two lossy stages, a torque on a and one on c.  Rolling forwards, a
stage's input loses (1/eta - 1) r |T| where it drives (T, the tooth load at the output, pushes the output
forwards) and (1 - eta_b) r |T| where the output drives it back, r the output's speed over the input's.
With every torque constant the shafts accelerate uniformly, at the rate that balances a's torque with
what the stages pass on, one stage inside the other:
    J_a alpha = tau_a - r1 k1 (J_b r1 alpha + r2 k2 (J_c r1 r2 alpha - tau_c)),
k = 1/eta where the input drives, eta_b where the output does.
"""

from __future__ import annotations

import numpy as np
import pytest

from hoistsim import scenario_from_dict, simulate

J_A, J_B, J_C = 0.5, 2.0, 30.0
N1, N2 = 3.0, 4.0  # each stage's input speed over its output's
ETA, ETA_B = (0.9, 0.95), (0.8, 0.85)


def scene(tau_a: float, tau_c: float) -> dict:
    stage = [{"efficiency": e, "backdrive_efficiency": b} for e, b in zip(ETA, ETA_B)]
    return {"name": "lossy-gear-train", "drivetrain": {
        "shafts": {"a": {"inertia": f"{J_A} kg*m^2", "speed": "50 rad/s"}, "b": {"inertia": f"{J_B} kg*m^2"},
                   "c": {"inertia": f"{J_C} kg*m^2"}},
        "torques": [{"shaft": "a", "torque": f"{tau_a} N*m"}, {"shaft": "c", "torque": f"{tau_c} N*m"}],
        "gears": {"first": {"between": ["a", "b"], "ratio": N1, **stage[0]},
                  "second": {"between": ["b", "c"], "ratio": N2, **stage[1]}}},
        "simulation": {"duration": "1 s", "output_interval": "10 ms", "rtol": 1e-10, "atol": 1e-12}}


def closed_form(tau_a: float, tau_c: float, drives: bool):
    r1, r2 = 1 / N1, 1 / N2
    k1, k2 = (1 / ETA[0], 1 / ETA[1]) if drives else ETA_B
    alpha = (tau_a + r1 * k1 * r2 * k2 * tau_c) / (J_A + r1 * k1 * (J_B * r1 + r2 * k2 * J_C * r1 * r2))
    second = J_C * r1 * r2 * alpha - tau_c  # tooth loads at each stage's output
    first = J_B * r1 * alpha + r2 * k2 * second
    return alpha, first, second


@pytest.mark.parametrize("tau_a, tau_c, drives, mode", [(40.0, -200.0, True, 1), (0.0, 300.0, False, 2)],
                         ids=["the input drives", "the output drives back"])
def test_two_lossy_stages_in_closed_form(tau_a, tau_c, drives, mode):
    run = simulate(scenario_from_dict(scene(tau_a, tau_c)))
    alpha, first, second = closed_form(tau_a, tau_c, drives)
    t = run["time"]
    np.testing.assert_allclose(run["a_speed"], 50.0 + alpha * t, rtol=0, atol=1e-8)
    np.testing.assert_allclose(run["c_speed"], (50.0 + alpha * t) / (N1 * N2), rtol=0, atol=1e-9)
    np.testing.assert_allclose(run["first_mesh_torque"], first, rtol=1e-9)
    np.testing.assert_allclose(run["second_mesh_torque"], second, rtol=1e-9)
    assert (run["first_mesh_mode"] == mode).all() and (run["second_mesh_mode"] == mode).all()
    # the first stage loses at a what it costs on top of passing its tooth load on: sum of powers
    k1 = 1 / ETA[0] - 1 if drives else 1 - ETA_B[0]
    speed_a = 50.0 + alpha * t
    lost = np.trapezoid(k1 * abs(first) / N1 * speed_a, t)
    assert run.summary["first_mesh_loss_energy"] == pytest.approx(lost, rel=1e-9)
    assert run.summary["energy_relative_residual"] < 1e-9

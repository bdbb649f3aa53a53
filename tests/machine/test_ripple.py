"""Torque ripples against the angle-domain energy theorem, and the angles they bring.

With every torque a function of angle only and the clutch locked, the machine
is one body of constant inertia J on the motor shaft, and the energy theorem
integrates exactly: 1/2 J w(theta)^2 = 1/2 J w0^2 + integral of (M_m - M_r) dtheta.
The reference below writes that integral out itself (no code of the engine).
"""

from __future__ import annotations

import copy
import math

import numpy as np
import pytest
from helpers import EXERCISE6

from hoistsim import scenario_from_dict, simulate
from hoistsim.machine.assemble import build_plan
from hoistsim.machine.elements import MotorRipple

TAU = 90 / 17  # pinion turns per drum turn
R, G = 0.2, 9.81
W0 = 10.0  # rad/s at the motor at the start


def _scene(motor_torque=600.0, mass=300.0, ripple=None, resisting=None, duration="2 s", rtol=1e-10):
    data = copy.deepcopy(EXERCISE6)
    data["motor"] = {"torque": f"{motor_torque} N*m", "inertia": "0.9 kg*m^2"}
    if ripple is not None:
        data["motor"]["ripple"] = ripple
    if resisting is not None:
        data["drum"]["resisting_ripple"] = resisting
    data["clutch"]["engagement_force"] = "20 kN"  # holds whatever the ripple does
    data["load"]["mass"] = f"{mass} kg"
    data["initial"] = {"motor_speed": W0, "drum_speed": W0 * 17 / 90}
    data["simulation"].update(duration=duration, output_interval="2 ms", rtol=rtol, atol=rtol / 100)
    return scenario_from_dict(data)


def _harmonic_work(theta, harmonics, period):
    """Integral over [0, theta] of sum A sin(k 2 pi t / period + phi), written out."""
    total = 0.0
    for k, amplitude, phase in harmonics:
        rate = 2 * math.pi * k / period
        total = total + amplitude / rate * (math.cos(phase) - np.cos(rate * theta + phase))
    return total


def _energy_reference(theta, motor_torque, mass, work):
    """Motor speed from the energy theorem at motor angles theta (the run's own)."""
    inertia = 0.9 + (40.0 + mass * R**2) / TAU**2
    load_torque = mass * G * R / TAU
    energy = 0.5 * inertia * W0**2 + (motor_torque - load_torque) * theta + work(theta)
    return np.sqrt(2 * energy / inertia)


@pytest.mark.slow
def test_motor_ripple_follows_the_energy_theorem():
    harmonics = [(3, 250.0, 0.0), (1, 120.0, math.radians(40))]
    period = 4 * math.pi  # a four-stroke engine: 720 deg
    ripple = {"period": "720 deg", "harmonics": [{"order": k, "amplitude": f"{a} N*m", "phase": f"{math.degrees(p)} deg"}
                                                for k, a, p in harmonics]}
    run = simulate(_scene(ripple=ripple))
    assert run.events["kind"].tolist() == [] and np.all(run["clutch_locked"] == 1)
    expected = _energy_reference(run["motor_angle"], 600.0, 300.0, lambda th: _harmonic_work(th, harmonics, period))
    assert np.max(np.abs(run["motor_speed"] - expected) / expected) < 1e-8
    assert run["motor_angle"][-1] > 4 * period  # several periods, the speed rippling
    assert run.energy_balance["relative_residual"] < 1e-8


@pytest.mark.slow
def test_resisting_ripple_on_the_drum_follows_the_energy_theorem():
    # one drum turn as a table: a cam-like resisting torque, zero mean removed by nothing
    table = [[0.0, 0.0], [math.pi / 2, 900.0], [math.pi, 0.0], [3 * math.pi / 2, -300.0], [2 * math.pi, 0.0]]
    resisting = {"table": [[f"{a!r} rad", f"{m} N*m"] for a, m in table]}
    # measured: 4.5e-12 at rtol 1e-11, 7.9e-10 at rtol 1e-10 (docs/numerics.md, "Angles and kinks")
    run = simulate(_scene(motor_torque=400.0, resisting=resisting, duration="3 s", rtol=1e-11))
    assert np.all(run["clutch_locked"] == 1)
    angles, torques = np.array(table).T

    def drum_work(theta_drum):  # integral of the table over [0, theta_drum]: whole turns, then exact pieces
        turns, rest = np.divmod(theta_drum, 2 * math.pi)
        knots = np.concatenate([[0.0], np.cumsum(0.5 * (torques[1:] + torques[:-1]) * np.diff(angles))])
        i = np.clip(np.searchsorted(angles, rest, side="right") - 1, 0, len(angles) - 2)
        slope = np.diff(torques)[i] / np.diff(angles)[i]
        into = rest - angles[i]
        return turns * knots[-1] + knots[i] + torques[i] * into + 0.5 * slope * into**2

    # the resisting torque on the drum does -work; at the motor shaft theta_drum = theta / tau
    expected = _energy_reference(run["drum_angle"] * TAU, 400.0, 300.0, lambda th: -drum_work(th / TAU))
    # the table's knots (four a drum turn, over ten turns) stepped over inside the passes, not each a pass's end
    # (56 passes when they were): a step ends just short of each, the next just past it
    assert run.stats["segments"] < 40, run.stats
    assert np.max(np.abs(run["motor_speed"] - expected) / expected) < 1e-8
    assert run["drum_angle"][-1] > 10 * 2 * math.pi
    assert run.energy_balance["relative_residual"] < 1e-8


def test_an_angle_is_a_state_only_where_an_element_reads_it():
    # the load is a mass on a line: its position (its height) is the one angle every hoist keeps
    plain = build_plan(_scene())[0].layout
    assert [n for n in plain.state_names if n.endswith("_angle")] == ["load_angle"]
    rippled = build_plan(_scene(ripple={"harmonics": [{"order": 1, "amplitude": "100 N*m"}]}))[0].layout
    assert sorted(n for n in rippled.state_names if n.endswith("_angle")) == ["load_angle", "motor_angle"]
    assert rippled.columns()["motor_angle"][0] == "rad"


@pytest.mark.parametrize("angle", [0.0, 1.0, 6.2, 6.3, 40.0, -3.0])
def test_table_ripple_work_is_its_integral(angle):
    ripple = MotorRipple(period=2 * math.pi, orders=np.zeros(0), amplitudes=np.zeros(0), phases=np.zeros(0),
                         table_angles=np.array([0.0, 1.0, 4.0, 2 * math.pi]),
                         table_torques=np.array([50.0, 300.0, -120.0, 50.0]), form="table")
    fine = np.linspace(0.0, angle, 200_001)
    numeric = np.trapezoid([float(ripple.torque_at(a)) for a in fine[::100]], fine[::100]) if angle else 0.0
    exact_fine = np.trapezoid(np.interp(np.mod(fine, 2 * math.pi), [0.0, 1.0, 4.0, 2 * math.pi],
                                        [50.0, 300.0, -120.0, 50.0]), fine)
    assert float(ripple.work_to(angle)) == pytest.approx(exact_fine, rel=1e-7, abs=1e-7)
    assert numeric == pytest.approx(exact_fine, rel=1e-3, abs=1e-3)

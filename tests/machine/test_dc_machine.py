"""A permanent-magnet DC machine (drivetrain.dc_machines), against independent answers.

- Modelica's DCPM_Start (scenarios/modelica/DCPM_Start.yaml) against Dymola's published trajectories: the
  armature current, the load's angle and speed within 1e-3 of their ranges.
- A voltage step against a constant load: a linear system of second order, x' = A x + b, whose exact solution
  is the matrix exponential of its augmented matrix (scipy's expm), not an integration.
- The nameplate's flux constant, the ledger (electrical energy in = copper loss + magnetic energy + kinetic
  energy + the load's work) and the summary's peak current, exact at its row.
- Bad input: one line naming the key, nothing written.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import SCENARIOS, part_keys_set, refused_in_one_line
from modelica_reference import deviations, signals
from scipy.linalg import expm

from hoistsim import load_scenario, scenario_from_text, simulate

DCPM = SCENARIOS / "modelica" / "DCPM_Start.yaml"
R, L, J = 0.05, 1.5e-3, 0.3  # ohm, H, kg*m^2: the record's armature and the rotor's and the load's inertia
FLUX = (100.0 - R * 100.0) / (1425.0 * math.pi / 30.0)  # V*s: the nameplate's induced voltage over its speed


def _scene(voltage: str, load: str, extra: str = "") -> str:
    """DCPM_Start's machine with its voltage and load torque tables given (three rows each: its structure)."""
    return f"""
name: dc-step
drivetrain:
  shafts:
    shaft: {{inertia: 0.15 kg*m^2, angle: 0 rad}}
  dc_machines:
    dcpm:
      shaft: shaft
      armature_resistance: 0.05 ohm
      armature_inductance: 1.5 mH
      nominal: {{voltage: 100 V, current: 100 A, speed: 1425 rpm}}
      rotor_inertia: 0.15 kg*m^2
      voltage: {voltage}
{extra}  torques:
    - {{shaft: shaft, torque: {load}}}
simulation:
  duration: 2 s
  output_interval: 1 ms
  rtol: 1e-10
  atol: 1e-12
"""


@pytest.fixture(scope="module")
def dcpm_start():
    return simulate(load_scenario(DCPM))


def test_dcpm_start_against_dymolas_published_trajectories(dcpm_start):
    """Within 1e-3 of each signal's range (measured: the current 8.7e-5, the speed 2.6e-6, the angle 1.3e-7)."""
    run = dcpm_start
    worst = deviations(run, "DCPM_Start", signals("DCPM_Start", run))
    assert max(worst.values()) < 2e-4, worst
    assert run.summary["energy_relative_residual"] < 1e-10


def test_a_voltage_step_against_a_constant_load_is_the_matrix_exponential():
    """L i' = V - R i - k w, J w' = k i - T: z = (i, w, 1), z' = M z, z(t) = expm(M t) z(0): every row."""
    volts, torque = 80.0, 30.0
    run = simulate(scenario_from_text(_scene(f"[[0 s, {volts} V], [0.2 s, {volts} V], [1 s, {volts} V]]",
                                             f"[[0 s, {-torque} N*m], [1.5 s, {-torque} N*m], [1.5 s, {-torque} N*m]]")))
    m = np.array([[-R / L, -FLUX / L, volts / L], [FLUX / J, 0.0, -torque / J], [0.0, 0.0, 0.0]])
    exact = np.array([expm(m * t) @ np.array([0.0, 0.0, 1.0]) for t in run.time])
    np.testing.assert_allclose(run["dcpm_current"], exact[:, 0], rtol=0, atol=1e-7 * np.ptp(exact[:, 0]))
    np.testing.assert_allclose(run["shaft_speed"], exact[:, 1], rtol=0, atol=1e-7 * np.ptp(exact[:, 1]))
    # at rest again: the current that holds the load, the speed where the induced voltage leaves it that drop
    settled = (torque / FLUX, (volts - R * torque / FLUX) / FLUX)
    assert (run["dcpm_current"][-1], run["shaft_speed"][-1]) == (pytest.approx(settled[0], rel=1e-6),
                                                                  pytest.approx(settled[1], rel=1e-6))
    np.testing.assert_allclose(run["dcpm_torque"], FLUX * run["dcpm_current"], rtol=1e-14)


def test_the_ledger_closes_with_the_electrical_energy_the_copper_loss_and_the_magnetic_energy(dcpm_start):
    run = dcpm_start
    power = run["dcpm_voltage"] * run["dcpm_current"]
    np.testing.assert_allclose(run["dcpm_power"], power, rtol=1e-14)
    energy = run.energy_balance["dcpm_electrical_energy"]
    copper = run.energy_balance["dcpm_copper_loss"]
    assert energy == pytest.approx(np.trapezoid(power, run.time), rel=1e-4)  # the rows' sum: a check of the state
    assert copper == pytest.approx(np.trapezoid(R * run["dcpm_current"] ** 2, run.time), rel=1e-4)
    magnetic = 0.5 * L * run["dcpm_current"][-1] ** 2
    assert run.energy_balance["dcpm_magnetic_energy_change"] == pytest.approx(magnetic, rel=1e-12)
    kinetic = 0.5 * J * run["loadInertia_speed"][-1] ** 2
    assert energy + run.energy_balance["torque1_work"] == pytest.approx(copper + magnetic + kinetic, rel=1e-11)
    assert run.summary["energy_relative_residual"] < 1e-10


def test_the_peak_current_is_exact_at_its_own_row(dcpm_start):
    run = dcpm_start
    peak = run.summary["dcpm_peak_current"]
    assert peak == pytest.approx(np.max(np.abs(run["dcpm_current"])), rel=1e-12) and peak > 110.0
    rows = run.instants["time"][run.instants["kind"] == "dcpm_current_peak"]
    assert np.any(np.isclose(rows, run.time[np.argmax(run["dcpm_current"])], atol=1e-12))


def test_the_nameplate_gives_the_flux_constant():
    machine = load_scenario(DCPM).drivetrain.dc_machines["dcpm"]
    assert machine.flux() == pytest.approx(FLUX, rel=1e-15) and machine.flux() == pytest.approx(0.6366, abs=1e-4)


@pytest.mark.parametrize("change, key, says", [
    ({"armature_resistance": "-0.05 ohm"}, "drivetrain.dc_machines.dcpm.armature_resistance", "must not be negative"),
    ({"flux_constant": "0.6 V*s"}, "drivetrain.dc_machines.dcpm.flux_constant", "one of the two"),
    ({"nominal": None}, "drivetrain.dc_machines.dcpm.flux_constant", "one of the two"),
    ({"shaft": "rotor"}, "drivetrain.dc_machines.dcpm.shaft", "no shaft 'rotor'"),
    ({"nominal": {"voltage": "4 V", "current": "100 A", "speed": "1425 rpm"}},
     "drivetrain.dc_machines.dcpm.nominal.voltage", "induce no voltage"),
])
def test_bad_input_names_its_key(change, key, says, tmp_path):
    refused_in_one_line(DCPM, part_keys_set("dc_machines", "dcpm", change), key, says, tmp_path)
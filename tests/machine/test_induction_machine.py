"""A squirrel-cage induction machine (drivetrain.induction_machines), against independent answers.

Modelica's IMC_DOL and IMC_YD reference files are too large to keep, so the examples (Modelica's default machine
record, its load) are held to an independent integration of the same space-phasor equations written otherwise
(the currents as states, the torque as 3/2 p L_m Im(conj(i_r) i_s)), scipy's DOP853 at rtol 1e-12; the settled
state to the machine's equivalent circuit, whose torque through its Thevenin equivalent is Kloss's formula with
the stator resistance's term, exactly.  The ledger closes; bad records are one line naming the key.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import SCENARIOS, part_keys_set, refused_in_one_line
from scipy.integrate import solve_ivp

from hoistsim import load_scenario, simulate

DOL, YD = SCENARIOS / "modelica" / "IMC_DOL.yaml", SCENARIOS / "modelica" / "IMC_YD.yaml"
P, RS, RR = 2, 0.03, 0.04
LSS = LRS = 3 * (1 - math.sqrt(1 - 0.0667)) / (2 * math.pi * 50)
LM = 3 * math.sqrt(1 - 0.0667) / (2 * math.pi * 50)
J = 0.29 + 0.29
LOAD, LOAD_SPEED = 161.4, 1440.45 * math.pi / 30
OMEGA = 2 * math.pi * 50


def _winding_voltage(t, star_until):
    """The windings' voltage space phasor: 100 V line to line, phase 1 a sine; star (a 1/sqrt(3) of it, 30
    degrees behind) until ``star_until`` (0: delta throughout)."""
    star = t < star_until
    amplitude = math.sqrt(2) * 100 * (1 / math.sqrt(3) if star else 1.0)
    return amplitude * np.exp(1j * (OMEGA * t - math.pi / 2 - (math.pi / 6 if star else 0.0)))


def _independent(on: float, star_until: float, end: float, times):
    """The machine and its load by scipy: states (i_s, i_r) in the stator's frame and the speed."""
    inductance = np.array([[LSS + LM, LM], [LM, LRS + LM]])

    def rates(t, y, star_until):
        i_s, i_r, w = y[0] + 1j * y[1], y[2] + 1j * y[3], y[4]
        psi_r = LM * i_s + (LRS + LM) * i_r
        d_i = np.linalg.solve(inductance, np.array([_winding_voltage(t, star_until) - RS * i_s,
                                                    -RR * i_r + 1j * P * w * psi_r]))
        torque = 1.5 * P * LM * np.imag(np.conj(i_r) * i_s)
        load = -LOAD * (w / LOAD_SPEED) ** 2 * np.sign(w)
        return [d_i[0].real, d_i[0].imag, d_i[1].real, d_i[1].imag, (torque + load) / J]

    out, y, start = [], np.zeros(5), on
    for stop in [b for b in (star_until,) if on < b < end] + [end]:  # the star-delta switch: a boundary
        chosen = times[(times >= start) & (times <= stop)]
        sol = solve_ivp(rates, (start, stop), y, method="DOP853", rtol=1e-12, atol=1e-12, t_eval=chosen,
                        args=(star_until,))
        out.append(sol.y if not out else sol.y[:, 1:] if chosen[0] == start else sol.y)
        y, start = sol.y[:, -1], stop
    return np.concatenate(out, axis=1)


@pytest.fixture(scope="module")
def dol():
    return simulate(load_scenario(DOL))


@pytest.mark.slow  # the independent integration takes some 20 s
@pytest.mark.parametrize("path, star_until, end", [(DOL, 0.0, 1.5), (YD, 2.0, 2.5)], ids=["IMC_DOL", "IMC_YD"])
def test_the_examples_against_an_independent_integration_of_the_same_equations(path, star_until, end):
    run = simulate(load_scenario(path))
    on = run.time >= 0.1
    times = np.unique(run.time[on])
    states = _independent(0.1, star_until, end, times)
    speed = np.interp(times, run.time, run["loadInertia_speed"])
    current = np.interp(times, run.time, run["aimc_current"])
    assert np.max(np.abs(speed - states[4])) < 1e-8 * np.max(np.abs(states[4]))
    assert np.max(np.abs(current - np.abs(states[0] + 1j * states[1]))) < 1e-8 * np.max(current)
    assert run.summary["energy_relative_residual"] < 1e-8


def _equivalent_circuit_torque(speed: float, amplitude: float) -> float:
    """The steady torque at ``speed`` (rad/s) of the machine fed sqrt(2) V per winding: the air-gap power
    3/2 |I_r|^2 R_r / s over the synchronous speed, the currents of the circuit R_s + j w L_ss, then j w L_m in
    parallel with R_r / s + j w L_rs."""
    slip = 1 - P * speed / OMEGA
    rotor = RR / slip + 1j * OMEGA * LRS
    main = 1j * OMEGA * LM
    stator_current = amplitude / (RS + 1j * OMEGA * LSS + main * rotor / (main + rotor))
    rotor_current = stator_current * main / (main + rotor)
    return 1.5 * abs(rotor_current) ** 2 * RR / slip * P / OMEGA


def _kloss(speed: float, amplitude: float) -> float:
    """Kloss's formula with the stator's term, T = 2 T_k (1 + a s_k) / (s / s_k + s_k / s + 2 a s_k), its
    breakdown torque T_k, slip s_k and a = R_th / R_r from the circuit's Thevenin equivalent seen by the rotor."""
    main = 1j * OMEGA * LM
    thevenin = (RS + 1j * OMEGA * LSS) * main / (RS + 1j * OMEGA * LSS + main)
    source = amplitude * main / (RS + 1j * OMEGA * LSS + main)
    r_th, x = thevenin.real, thevenin.imag + OMEGA * LRS
    s_k = RR / math.hypot(r_th, x)
    t_k = 1.5 * P / OMEGA * abs(source) ** 2 / (2 * (r_th + math.hypot(r_th, x)))
    a, slip = r_th / RR, 1 - P * speed / OMEGA
    return 2 * t_k * (1 + a * s_k) / (slip / s_k + s_k / slip + 2 * a * s_k)


def test_the_settled_state_is_the_equivalent_circuits_and_kloss(dol):
    """At the end of IMC_DOL the machine turns at the speed where its torque meets the load's: the torque the
    simulation settles at is the circuit's at that speed and Kloss's (the two the same to round-off)."""
    speed, torque = dol["loadInertia_speed"][-1], dol["aimc_torque"][-1]
    amplitude = math.sqrt(2) * 100
    assert _kloss(speed, amplitude) == pytest.approx(_equivalent_circuit_torque(speed, amplitude), rel=1e-12)
    assert torque == pytest.approx(_equivalent_circuit_torque(speed, amplitude), rel=1e-6)
    assert torque == pytest.approx(LOAD * (speed / LOAD_SPEED) ** 2, rel=1e-6)
    assert speed == pytest.approx(LOAD_SPEED, rel=1e-5)  # the record's nominal point is the load's


def test_its_peaks_are_exact_and_its_ledger_closes(dol):
    run = dol
    assert run.summary["aimc_peak_current"] == pytest.approx(np.max(run["aimc_current"]), rel=1e-12)
    assert run.summary["aimc_max_torque"] == pytest.approx(np.max(run["aimc_torque"]), rel=1e-12)
    assert run.summary["aimc_min_torque"] == pytest.approx(np.min(run["aimc_torque"]), rel=1e-12)
    assert run.summary["aimc_min_torque"] < -250 and run.summary["aimc_max_torque"] > 550  # a DOL start's
    balance = run.energy_balance
    assert balance["aimc_electrical_energy"] == pytest.approx(np.trapezoid(run["aimc_power"], run.time), rel=1e-4)
    assert balance["relative_residual"] < 1e-8


@pytest.mark.parametrize("change, key, says", [
    ({"stator_resistance": "-0.03 ohm"}, "drivetrain.induction_machines.aimc.stator_resistance", "negative"),
    ({"rotor_leakage": "10 mH"}, "drivetrain.induction_machines.aimc.rotor_leakage", "main field"),
    ({"supply": {"voltage": "100 V", "frequency": "50 Hz", "connection": "star_delta"}},
     "drivetrain.induction_machines.aimc.supply.delta_at", "star-delta"),
])
def test_bad_input_names_its_key(change, key, says, tmp_path):
    refused_in_one_line(DOL, part_keys_set("induction_machines", "aimc", change), key, says, tmp_path)


@pytest.mark.slow  # a program of its own (the signals' rows) and the independent integration: some 20 s
def test_a_voltage_frequency_inverter_start_against_an_independent_integration():
    """IMC_DOL's machine and load fed by a V/f inverter: 0 to 100 V and 0 to 50 Hz over 1 s, held after (the
    supply's angle the integral of 2 pi f: 2 pi 25 t^2 on the ramp).  The same equations by scipy: the speed
    within 1e-8 of its range, the current within 1e-8 of its peak, and no start's torque swing: an inverter's
    start stays within a fraction of a direct-on-line start's peak current."""
    from ruamel.yaml import YAML

    data = YAML(typ="safe").load(DOL.read_text(encoding="utf-8"))
    data["drivetrain"]["induction_machines"]["aimc"]["supply"] = {
        "voltage": [["0 s", "0 V"], ["1 s", "100 V"]], "frequency": [["0 s", "0 Hz"], ["1 s", "50 Hz"]],
        "connection": "delta"}
    from hoistsim import scenario_from_dict

    run = simulate(scenario_from_dict(data))

    def angle(t):
        return 2 * math.pi * (25 * t * t if t < 1 else 25 + 50 * (t - 1))

    def voltage(t):
        return math.sqrt(2) * 100 * min(t, 1.0) * np.exp(1j * (angle(t) - math.pi / 2))

    inductance = np.array([[LSS + LM, LM], [LM, LRS + LM]])

    def rates(t, y):
        i_s, i_r, w = y[0] + 1j * y[1], y[2] + 1j * y[3], y[4]
        d_i = np.linalg.solve(inductance, np.array([voltage(t) - RS * i_s,
                                                    -RR * i_r + 1j * P * w * (LM * i_s + (LRS + LM) * i_r)]))
        torque = 1.5 * P * LM * np.imag(np.conj(i_r) * i_s)
        return [d_i[0].real, d_i[0].imag, d_i[1].real, d_i[1].imag,
                (torque - LOAD * (w / LOAD_SPEED) ** 2 * np.sign(w)) / J]

    times = np.unique(run.time)
    parts = [solve_ivp(rates, span, y0, method="DOP853", rtol=1e-12, atol=1e-12, t_eval=times[(times >= span[0])
                                                                                             & (times <= span[1])])
             for span, y0 in [((0.0, 1.0), np.zeros(5))]]
    after = solve_ivp(rates, (1.0, 1.5), parts[0].y[:, -1], method="DOP853", rtol=1e-12, atol=1e-12,
                      t_eval=times[times > 1.0])
    states = np.concatenate([parts[0].y, after.y], axis=1)
    speed = np.interp(times, run.time, run["loadInertia_speed"])
    current = np.interp(times, run.time, run["aimc_current"])
    assert np.max(np.abs(speed - states[4])) < 1e-8 * np.max(np.abs(states[4]))
    assert np.max(np.abs(current - np.abs(states[0] + 1j * states[1]))) < 1e-8 * np.max(current)
    assert run.summary["aimc_peak_current"] < 0.5 * 922.8  # IMC_DOL's direct-on-line peak
    assert run.summary["energy_relative_residual"] < 1e-8

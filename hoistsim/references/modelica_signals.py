"""Each of Modelica's examples (scenarios/modelica/) as it is held to Dymola's trajectories (:mod:`.dymola`): its
comparison signals worked out from a run's series, the tolerance on their worst deviation, and the instant the
comparison stops where it stops early.  The tests of the examples and the documentation's gallery read them here.

A Modelica relative signal of a part (``phi_rel``, ``w_rel``, ``s_rel``, ``v_rel``) is its flange b's less its
flange a's; between masses it runs between their ends (a mass's length is Modelica's L), worked out here from
their centres.  Rotational examples are keyed by their name, Translational ones ``translational/<name>``.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

# HeatLosses' block (massWithStopAndFriction) first reaches its upper stop here (Dymola's event; ours within
# 1e-7 s): from it on Dymola's trajectory keeps the stiff spring-damper's relative speed through the impact
HEAT_LOSSES_FIRST_IMPACT = 0.428549


@dataclass(frozen=True)
class Comparison:
    """What an example compares: ``signals(run)`` (Modelica's name -> our series on the run's rows), each within
    ``tolerance`` of its range, before ``until`` (s); ``why_until`` says why it stops there."""

    signals: Callable[[object], dict]
    tolerance: float = 1e-3
    until: float = np.inf
    why_until: str = ""


def _shaft(run, shaft: str) -> dict:
    return {f"{shaft}.phi": run[f"{shaft}_angle"], f"{shaft}.w": run[f"{shaft}_speed"]}


def _relative(run, part: str, a: str, b: str) -> dict:
    """Modelica's phi_rel and w_rel of ``part`` from shaft a to shaft b: b's less a's."""
    return {f"{part}.phi_rel": run[f"{b}_angle"] - run[f"{a}_angle"],
            f"{part}.w_rel": run[f"{b}_speed"] - run[f"{a}_speed"]}


def _twist(run, part: str) -> dict:
    """A spring's or a damper's phi_rel and w_rel, as it writes them."""
    return {f"{part}.phi_rel": run[f"{part}_twist"], f"{part}.w_rel": run[f"{part}_twist_speed"]}


def _masses(run, *masses: str) -> dict:
    return {f"{m}.{k}": run[f"{m}_{series}"] for m in masses for k, series in (("s", "position"), ("v", "velocity"))}


def _coupled_clutches(run) -> dict:
    signals = _shaft(run, "J1")
    for k in (1, 2, 3):
        signals |= _relative(run, f"clutch{k}", f"J{k}", f"J{k + 1}")
    return signals


ROTATIONAL = {
    "First": Comparison(lambda run: {**_twist(run, "damper"), **_shaft(run, "inertia3")}),
    "FirstGrounded": Comparison(lambda run: {**_twist(run, "damper"), **_shaft(run, "inertia3")}),
    "Backlash": Comparison(lambda run: {**_twist(run, "elastoBacklash"), **_twist(run, "springDamper")}),
    "Friction": Comparison(lambda run: {**_shaft(run, "inertia3"), **_relative(run, "clutch", "inertia3", "inertia2"),
                                        "spring.phi_rel": run["spring_twist"],
                                        "spring.w_rel": run["spring_twist_speed"]}),
    "OneWayClutch": Comparison(lambda run: {**_shaft(run, "inertiaIn"),
                                            **_relative(run, "oneWayClutch", "inertiaIn", "inertiaOut")}),
    "OneWayClutchDisengaged": Comparison(lambda run: {**_shaft(run, "inertiaIn"),
                                                      **_relative(run, "oneWayClutch", "inertiaIn", "inertiaOut")}),
    "SimpleGearShift": Comparison(lambda run: {**_shaft(run, "engine"), **_shaft(run, "load"),
                                               **_relative(run, "clutch", "engine", "ring")}),
    "CoupledClutches": Comparison(_coupled_clutches),
    "LossyGearDemo1": Comparison(lambda run: _shaft(run, "Inertia2")),
    "LossyGearDemo2": Comparison(lambda run: _shaft(run, "Inertia2")),
    "LossyGearDemo3": Comparison(lambda run: _shaft(run, "Inertia2")),
    "ElasticBearing": Comparison(lambda run: {**_shaft(run, "load"), **_shaft(run, "shaft"),
                                              **_twist(run, "springDamper")}),
    "EddyCurrentBrake": Comparison(lambda run: {"inertia.phi": run["inertia_angle"],
                                                "heatCapacitor.T": run["heatCapacitor_temperature"],
                                                "eddyCurrentTorque.lossPower": run["eddyCurrentTorque_loss_power"]},
                                   tolerance=1e-5),
    "RollingWheel": Comparison(lambda run: _shaft(run, "inertia"), tolerance=1e-5),
    "DCPM_Start": Comparison(lambda run: {"dcpm.la.i": run["dcpm_current"], **_shaft(run, "loadInertia")},
                             tolerance=2e-4),
    "PID_Controller": Comparison(lambda run: {"PI.I.y": run["PI_integral"], **_shaft(run, "inertia1"),
                                              "integrator.y": run["integrator_output"],
                                              **_relative(run, "spring", "inertia1", "inertia2")},
                                 tolerance=2e-4),
}


def _damper(run) -> dict:
    """The walls at 4.5 m: each part from its mass's right end (the mass 1 m long) to the wall."""
    parts = {"damper1": "mass1", "damper2": "mass2", "springDamper3": "mass3"}
    return {**{f"{p}.s_rel": 4.0 - run[f"{m}_position"] for p, m in parts.items()},
            **{f"{p}.v_rel": -run[f"{m}_velocity"] for p, m in parts.items()}}


def _initial_conditions(run) -> dict:
    """sd1 between m1 (1 m) and m2 (2 m), sd2 between m3 (3 m) and m4 (5 m)."""
    return {**_masses(run, "m1", "m3"),
            "sd1.s_rel": run["m2_position"] - run["m1_position"] - 1.5,
            "sd1.v_rel": run["m2_velocity"] - run["m1_velocity"],
            "sd2.s_rel": run["m4_position"] - run["m3_position"] - 4.0,
            "sd2.v_rel": run["m4_velocity"] - run["m3_velocity"]}


def _preload(run) -> dict:
    """The parts' s_rel from the centres, the rods and the fixed points (PreLoad.yaml)."""
    return {"friction.v_rel": run["spool_velocity"],
            "innerContactA.s_rel": run["springPlateA_position"] - run["spool_position"] + 0.10875,
            "innerContactB.s_rel": run["spool_position"] - run["springPlateB_position"] - 0.08125,
            "outerContactA.v_rel": run["springPlateA_velocity"],
            "outerContactB.s_rel": -run["springPlateB_position"] - 0.066,
            "outerContactB.v_rel": -run["springPlateB_velocity"]}


def _heat_losses(run) -> dict:
    """s_rel from the blocks' centres (each 0.1 m long), the damper's from mass1's left end to the wall."""
    s1, v1 = run["mass1_position"], run["mass1_velocity"]
    s4, v4 = run["massWithStopAndFriction_position"], run["massWithStopAndFriction_velocity"]
    return {"damper.s_rel": 0.05 - s1, "damper.v_rel": -v1, "massWithStopAndFriction.s": s4,
            "massWithStopAndFriction.v": v4, "springDamper.s_rel": run["mass2_position"] - s1 - 0.1,
            "springDamper.v_rel": run["mass2_velocity"] - v1, "springDamper1.s_rel": s4 - run["mass3_position"] - 0.1,
            "springDamper1.v_rel": v4 - run["mass3_velocity"]}


TRANSLATIONAL = {
    # the source's flange: the mass's left end (each mass 1 m long: its ends half a metre from its centre)
    "Accelerate": Comparison(lambda run: {"accelerate.s": run["mass_position"] - 0.5,
                                          "accelerate.v": run["mass_velocity"]}),
    "SignConvention": Comparison(lambda run: _masses(run, "mass1", "mass2", "mass3")),
    "Sensors": Comparison(lambda run: _masses(run, "mass")),
    "Damper": Comparison(_damper),
    "Oscillator": Comparison(lambda run: {"damper1.s_rel": 0.5 - run["mass2_position"],  # the wall at 1 m
                                          "damper1.v_rel": -run["mass2_velocity"], **_masses(run, "mass1")}),
    "InitialConditions": Comparison(_initial_conditions),
    "WhyArrows": Comparison(lambda run: _masses(run, "inertia2", "mass1")),
    # from the point at -2 m to a mass, or from a mass to the point at 2 m
    "ElastoGap": Comparison(lambda run: {"elastoGap1.v_rel": run["mass2_velocity"],
                                         "elastoGap2.s_rel": 2.0 - run["mass2_position"],
                                         "springDamper1.v_rel": run["mass1_velocity"],
                                         "springDamper2.s_rel": 2.0 - run["mass1_position"]}),
    "EddyCurrentBrake": Comparison(lambda run: {"eddyCurrentForce.lossPower": run["eddyCurrentForce_loss_power"],
                                                "mass.s": run["mass_position"],
                                                "heatCapacitor.T": run["heatCapacitor_temperature"]}),
    "Brake": Comparison(lambda run: _masses(run, "mass1", "mass2")),
    # the direct mass's own mass, with the inverse mass it drives: one body
    "GenerationOfFMUs": Comparison(lambda run: {**_masses(run, "mass2a", "mass2b", "mass3a", "mass3b"),
                                                "directMass.mass.s": run["directMass_position"],
                                                "directMass.mass.v": run["directMass_velocity"]}),
    "PreLoad": Comparison(_preload),
    "Friction": Comparison(lambda run: _masses(run, "mass", "stop1", "stop2")),
    "HeatLosses": Comparison(_heat_losses, until=HEAT_LOSSES_FIRST_IMPACT, why_until=(
        "after the block's first impact on its stop Dymola's trajectory keeps the stiff spring-damper's relative "
        "speed through the impact (Modelica's SpringDamper prefers it as a state, and the stop resets the block's "
        "speed alone): mass3 stops with the block there, where hoistsim's runs on into the damper, no impulse "
        "passing a spring-damper")),
    "Vehicle": Comparison(lambda run: _masses(run, "vehicle", "vehicle1", "trailer")),
}

COMPARISONS: dict[str, Comparison] = {**ROTATIONAL, **{f"translational/{name}": comparison
                                                       for name, comparison in TRANSLATIONAL.items()}}

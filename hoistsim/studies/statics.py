"""The exercise's static answers for a scenario's machine, in exact arithmetic.

1. Axial force for the clutch to carry the stall torque C0 without slipping.
2. Clutch capacity at the scenario's engagement force, and the heaviest load
   lifted at constant speed with the clutch adhering; the tooth forces then.
3. Drum-shaft bearing reactions in that condition (needs ``bearings:``).

Plus one answer statics alone gets wrong: the least force for a start from rest
without slip.  While the motor accelerates its own inertia takes part of C0,
so the clutch carries only T_c(0) = (J_b C0 + J_a T_L)/(J_a + J_b) < C0; and as
the motor speeds up C(omega) falls, so t = 0 is the worst instant.

Exercise 6 assumes an ideal mesh.  With ``gears.efficiency`` eta the pinion
drives the wheel with eta of its power: the wheel's torque, the heaviest load
and the drum-shaft forces take eta, and lifting from rest the drum side
(inertia and load torque) weighs 1/eta as much on the clutch.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

from ..components import DrumShaft
from ..references.model import Machine
from ..scenario.loading import Scenario


@dataclass(frozen=True)
class Answer:
    key: str  # the JSON name
    symbol: str
    quantity: str
    value: float
    unit: str


def holding_force(scenario: Scenario) -> float:
    """The engagement force the clutch is held at once engaged (the table's last value, N)."""
    return scenario.clutch.engagement_force.forces[-1]


def _lifting(scenario: Scenario):
    """The reduced machine as the clutch sees it lifting: drum side (inertia, load torque) over eta."""
    machine = Machine.from_scenario(scenario)
    d = machine.reduced()
    eta, _ = scenario.gears.efficiencies
    pinion_side = machine.driven_inertia + machine.gears.pinion_inertia
    return replace(d, output_inertia=pinion_side + (d.output_inertia - pinion_side) / eta,
                   load_torque=d.load_torque / eta)


def least_force_for_start(scenario: Scenario) -> float:
    """Least constant axial force (N) for a start from rest without any slip, for the scene's load."""
    d = _lifting(scenario)
    peak = (d.output_inertia * d.stall_torque + d.motor_inertia * d.load_torque) / (
        d.motor_inertia + d.output_inertia)
    return peak / (d.static_friction * d.clutch_constant)


def warnings(scenario: Scenario) -> list[str]:
    """What makes some answers meaningless for this scenario: a load the motor or the clutch cannot hold."""
    d = _lifting(scenario)
    force = holding_force(scenario)
    capacity = d.static_capacity(force)
    mass = scenario.load.mass
    out = []
    if d.load_torque >= d.stall_torque:
        out.append(f"load.mass: {mass:g} kg puts {d.load_torque:.4g} N*m on the motor shaft, more than the motor's "
                   f"stall torque ({d.stall_torque:.4g} N*m): no engagement force lifts it, and the least start "
                   "force (least_force_for_start) only says when the clutch would not slip")
    eta, eta_back = scenario.gears.efficiencies
    overhauling = d.load_torque * eta * eta_back  # what the load passes back through the mesh
    if capacity <= overhauling:
        out.append(f"clutch.engagement_force: at {force:g} N the clutch holds {capacity:.4g} N*m, less than the "
                   f"load's {overhauling:.4g} N*m: the load runs back whatever the motor does")
    return out


def answers(scenario: Scenario) -> list[Answer]:
    machine = Machine.from_scenario(scenario)
    clutch, gears = machine.clutch, machine.gears
    force = holding_force(scenario)
    capacity = clutch.static_capacity(force)  # M_f
    tangential = gears.tangential_force(capacity)  # T = M_f / r1
    radial = gears.radial_force(tangential)  # N = T tan(alpha)
    # Wheel torque eta T r2 holds the rope at the drum radius: P = eta T r2 / R = eta M_f tau / R.
    eta, eta_back = scenario.gears.efficiencies
    max_weight = eta * tangential * gears.wheel_pitch_radius / machine.drum.rope_radius
    rows = [
        Answer("engagement_force_for_stall_torque", "F_A", "axial force for C0 without slip (Q1)",
               clutch.force_for_torque(machine.motor.stall_torque), "N"),
        Answer("least_force_for_start", "F_min", "least axial force, start from rest without slip",
               least_force_for_start(scenario), "N"),
        Answer("engagement_force", "F", "scenario's engagement force (held)", force, "N"),
        Answer("clutch_capacity", "M_f", "static clutch capacity at F", capacity, "N*m"),
        Answer("mesh_efficiency", "eta", "mesh efficiency, pinion driving (exercise 6: ideal, 1)", eta, "1"),
        Answer("backdrive_efficiency", "eta_b", "mesh efficiency, wheel driving (exercise 6: ideal, 1)",
               eta_back, "1"),
        Answer("max_load_weight", "P_max", "heaviest load lifted at constant speed (Q2), eta M_f tau / R",
               max_weight, "N"),
        Answer("max_load_mass", "M_max", "its mass, P_max / g", max_weight / machine.load.gravity
               if machine.load.gravity > 0 else float("inf"), "kg"),
        Answer("tooth_tangential_force", "T", "tangential tooth force, M_f / r1", tangential, "N"),
        Answer("tooth_radial_force", "N", "radial tooth force, T tan(alpha)", radial, "N"),
        Answer("tooth_force", "F_12", "total tooth force", (tangential**2 + radial**2) ** 0.5, "N"),
        Answer("rope_tension", "P", "rope tension at constant speed", max_weight, "N"),
    ]
    if scenario.bearings is not None:
        b = scenario.bearings
        # the wheel passes eta T to the drum shaft (what holds P at the rope)
        reactions = DrumShaft(b.gear_offset, b.rope_offset, b.span).reactions(eta * tangential, radial, max_weight)
        names = {"bearing_A_x": "R_AX", "bearing_A_y": "R_AY", "bearing_A": "R_A",
                 "bearing_B_x": "R_BX", "bearing_B_y": "R_BY", "bearing_B": "R_B"}
        for key, symbol in names.items():
            where = "bearing A" if "_A" in key else "bearing B"
            part = {"x": "component in the plane of T", "y": "component in the plane of N and P"}.get(
                key[-1], "reaction (magnitude)")
            rows.append(Answer(key, symbol, f"{where} {part} (Q3)", reactions[key], "N"))
    return rows


def as_dict(scenario: Scenario) -> dict[str, float]:
    return {a.key: a.value for a in answers(scenario)}

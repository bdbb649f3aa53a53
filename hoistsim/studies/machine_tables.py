"""The machine a scenario stands for, as ``hoistsim check`` prints it: each body in its own quantity (a shaft's
inertia, a load's mass), an elastic rope's stiffness, the load's static stretch and natural frequency on it, and
the hoist's two-shaft reduced model, or a drawn drivetrain's shafts and clutches; then the parts the machine is
built from (the hoist's as its template draws them)."""

from __future__ import annotations

import math
import re

from ..results.report import fmt, table


def reduced_model_table(scenario, width: int | None = None) -> str:
    """The machine as the simulator sees it: each body, the rope, then the two-shaft numbers of exercise 6;
    within ``width`` characters (None: however wide), as :func:`hoistsim.results.report.table` wraps it."""
    from ..errors import ScenarioError
    from ..machine.assemble import machine_elements
    from ..references.model import Machine

    elements = machine_elements(scenario)
    rows = body_rows(elements) + motor_rows(elements) + rope_rows(elements)
    try:
        d = Machine.from_scenario(scenario).reduced()
    except ScenarioError:  # not the two-shaft hoist of exercise 6 (a motor that is not linear)
        return table(["symbol", "quantity", "value", "unit"], rows, align="llrl", width=width)
    force = scenario.clutch.engagement_force
    peak = max(force.forces)
    rows += [
        ["J_a", "motor-side inertia", fmt(d.motor_inertia), "kg*m^2"],
        ["J_b", "output-side inertia (at the pinion)", fmt(d.output_inertia), "kg*m^2"],
        ["tau", "gear ratio z2/z1", fmt(d.ratio), "-"],
        ["T_L", "load torque at the pinion", fmt(d.load_torque), "N*m"],
        ["c", "clutch constant n r_m / sin(beta)", fmt(d.clutch_constant), "m"],
        ["T_s", f"static capacity at {fmt(peak)} N", fmt(d.static_capacity(peak)), "N*m"],
        ["T_k", f"kinetic torque at {fmt(peak)} N", fmt(d.kinetic_torque(peak)), "N*m"],
    ]
    return table(["symbol", "quantity", "value", "unit"], rows, align="llrl", width=width)


def body_rows(elements) -> list[list[str]]:
    """Each body in its own quantity: a shaft's inertia (all the shafts it carries, reduced to it) in kg*m^2, a
    load that moves along its rope (a body of its own) by its mass in kg."""
    from ..machine.core.bodies import Bodies
    from ..machine.core.layout import Layout
    from ..machine.elements.elastic_load import ElasticLoad

    layout = Layout(elements)
    moving = {body for part in elements if isinstance(part, ElasticLoad) for body in part.bodies()}
    return [[f"m[{body}]", f"mass of the {body} body (it moves along its rope)", fmt(float(j)), "kg"]
            if body in moving else
            [f"J[{body}]", f"inertia of the {body} body (all its shafts carry, reduced)", fmt(float(j)), "kg*m^2"]
            for body, j in zip(layout.bodies, Bodies(layout).inertia)]


def motor_rows(elements) -> list[list[str]]:
    """Each motor's characteristic as ``check`` prints it: its torque at standstill, where it reaches zero and,
    for an induction motor (Kloss), its breakdown torque and the speed it gives it at; then its torque at five
    speeds from standstill to its no-load speed (a curve to read, the nameplate's numbers worked out)."""
    from ..machine.elements.kloss_motor import KlossMotor
    from ..machine.elements.linear_motor import LinearMotor
    from ..machine.elements.motor import Motor

    rows = []
    for motor in (part for part in elements if isinstance(part, Motor)):
        law, name = motor.law, motor.section
        if isinstance(law, LinearMotor):
            top = float(law.no_load_speed)
        elif isinstance(law, KlossMotor):
            top = float(law.synchronous_speed)
        else:  # a table or a constant torque: its curve says it
            continue
        rpm = 30.0 / math.pi
        rows += [[f"C0[{name}]", f"{name}'s torque at standstill", fmt(float(law.characteristic(0.0))), "N*m"],
                 [f"n0[{name}]", f"{name}'s no-load (synchronous) speed, where its torque is 0", fmt(top * rpm), "rpm"]]
        if isinstance(law, KlossMotor):
            speed = top * (1.0 - float(law.breakdown_slip))
            rows += [[f"T_b[{name}]", f"{name}'s breakdown torque, at {fmt(speed * rpm)} rpm (slip "
                                      f"{fmt(float(law.breakdown_slip))})", fmt(float(law.breakdown_torque)), "N*m"]]
        curve = ", ".join(f"{fmt(float(law.characteristic(top * k / 4)))} at {fmt(top * k / 4 * rpm)}"
                          for k in range(1, 4))
        rows += [[f"C[{name}]", f"{name}'s torque [N*m] at [rpm]", curve, ""]]
    return rows


def rope_rows(elements) -> list[list[str]]:
    """An elastic rope's numbers, as ``check`` prints them: its stiffness at the start (E A / L for a wire rope,
    else as given), the load's static stretch on it, m g / k, and the load's natural frequency on it with the
    drum held, sqrt(k / m).  None without an elastic rope."""
    from ..machine.elements.elastic_load import ElasticLoad
    from ..machine.elements.rope import Rope
    from ..machine.elements.wire_rope import WireRope

    loads = [part for part in elements if isinstance(part, ElasticLoad)]
    rows = []
    for rope in (part for part in elements if isinstance(part, (WireRope, Rope))):
        if isinstance(rope, WireRope):
            length = float(rope.free_length)
            stiffness = float(rope.axial_stiffness) / length
            how = f"E A / L at its free length L = {fmt(length)} m"
        else:
            stiffness = float(rope.constant_stiffness)
            how = "as given (whatever the length paid out)"
        mass = float(loads[0].mass)
        omega = (stiffness / mass) ** 0.5
        rows += [["k", f"rope stiffness, {how}", fmt(stiffness * 1e-3), "kN/m"],
                 ["s_st", "static stretch with the load hanging, m g / k", fmt(float(rope.weight) / stiffness * 1e3),
                  "mm"],
                 ["w_n", "load's natural frequency on the rope, drum held: sqrt(k / m)", fmt(omega), "rad/s"],
                 ["f_n", "the same in cycles, w_n / (2 pi)", fmt(omega / (2 * math.pi)), "Hz"]]
    return rows


def machine_table(scenario, width: int | None = None) -> str:
    """What ``check`` prints of a scenario's machine: the hoist's reduced model, or a drawn drivetrain (and its
    rope); then the parts it is built from; each table within ``width`` characters (None: however wide)."""
    if scenario.drivetrain is None:
        first = reduced_model_table(scenario, width)
    else:
        from ..machine.assemble import machine_elements

        elements = machine_elements(scenario)
        rope = rope_rows(elements)  # the shafts are in the drivetrain's table; the load on its rope here
        rope = [row for row in body_rows(elements) if row[-1] == "kg"] + rope if rope else []
        first = drivetrain_table(scenario.drivetrain, width) + (
            "\n\n" + table(["symbol", "quantity", "value", "unit"], rope, align="llrl", width=width) if rope else "")
    return first + "\n\n" + parts_table(scenario, width)


def parts_table(scenario, width: int | None = None) -> str:
    """Each part of the machine, as built: its name, its kind, where it sits (a shaft's gear train, the shafts a
    coupling joins, the shafts it brings inertia to) and the scenario section it comes from."""
    from ..machine.assemble import machine_elements
    from ..machine.core.element import AbstractCoupling
    from ..machine.elements import element_sections

    rows = []
    for (section, _, _), part in zip(element_sections(scenario), machine_elements(scenario)):
        if isinstance(part, AbstractCoupling):
            where = " - ".join(side or "ground" for side in part.joins())  # a linkage: its three shafts
        elif getattr(part, "geared_to", None):
            where = f"shaft, {fmt(float(part.speed_ratio))} x {part.geared_to}"
        elif part.bodies():
            where = "shaft (a body)"
        else:
            where = ", ".join(dict.fromkeys(shaft for shaft, _ in part.inertias())) or "-"
        rows.append([part.section, _words(type(part).__name__), where, section])
    return table(["part", "kind", "on", "from"], rows, align="llll", width=width)


def _words(name: str) -> str:
    """A class's name as words: FrictionClutch -> friction clutch."""
    return re.sub(r"(?<=[a-z])(?=[A-Z])", " ", name).lower()


def drivetrain_table(drivetrain, width: int | None = None) -> str:
    """A drawn drivetrain as ``check`` prints it: its shafts, then its clutches with their capacities at
    the largest force they are given (for a force in harmonics, the offset plus every amplitude)."""
    shafts = table(["shaft", "inertia [kg*m^2]", "speed at t = 0 [rad/s]"],
                   [[name, fmt(s.inertia), fmt(s.speed)] for name, s in drivetrain.shafts.items()], align="lrr",
                   width=width)
    rows = []
    for name, clutch in drivetrain.clutches.items():
        force = clutch.force
        largest = max(force.values) + sum(abs(a) for a in force.amplitudes)
        per = clutch.torque_per_newton * max(largest, 0.0)
        rows.append([name, " - ".join(clutch.between), fmt(largest), fmt(clutch.static_friction * per),
                     fmt(clutch.kinetic_at_rest * per)])
    clutches = table(["clutch", "between", "largest force [N]", "capacity [N*m]", "sliding [N*m]"], rows,
                     align="llrrr", width=width)
    return shafts + ("\n\n" + clutches if rows else "")

"""The new elements against independent answers, at rtol 1e-10: the largest errors.

- a flywheel of inertia X on the motor (or drum) shaft against the same scene with X added to that
  shaft's own inertia: speeds;
- a rim's inertia against pi rho s (R_o^4 - R_i^4) / 2;
- a torque-speed table lying on C0 (1 - omega/omega0) against the linear motor: speeds;
- a motor that is off, spinning at omega1, joined through a slipping clutch of kinetic torque T to a
  drum at rest: lock-up at J_a J_b omega1 / (T (J_a + J_b)), heat J_a J_b omega1^2 / (2 (J_a + J_b)).

    python benchmarks/elements_accuracy.py
"""

from __future__ import annotations

import copy
import math

import numpy as np

from hoistsim import scenario_from_dict, simulate
from hoistsim.components import ConeClutch

BASE = {
    "name": "elements-check",
    "motor": {"stall_torque": "500 N*m", "no_load_speed": "300 rpm", "inertia": "0.9 kg*m^2"},
    "clutch": {"inner_radius": "20 cm", "outer_radius": "24 cm", "half_angle": "25 deg", "static_friction": 0.3,
               "kinetic_friction": 0.1, "engagement_force": [["0 s", "0 N"], ["0.2 s", "0 N"], ["0.6 s", "6000 N"]]},
    "gears": {"pinion_teeth": 17, "wheel_teeth": 90, "module": "4 mm"},
    "drum": {"diameter": "40 cm", "inertia": "40 kg*m^2"},
    "load": {"mass": "500 kg"},
    "simulation": {"duration": "1.5 s", "output_interval": "5 ms", "rtol": 1e-10, "atol": 1e-12},
}


def scene(**sections):
    data = copy.deepcopy(BASE)
    for key, value in sections.items():
        data[key] = {k: v for k, v in {**data.get(key, {}), **value}.items() if v is not None}
    return scenario_from_dict(data)


def speed_error(a, b) -> float:
    return max(np.max(np.abs(a["motor_speed"] - b["motor_speed"])), np.max(np.abs(a["drum_speed"] - b["drum_speed"])))


def main() -> None:
    rows = []
    for shaft, section, base in (("motor", "motor", 0.9), ("drum", "drum", 40.0)):
        fly = simulate(scene(flywheel={"shaft": shaft, "inertia": "7.5 kg*m^2"}))
        plain = simulate(scene(**{section: {"inertia": f"{base + 7.5} kg*m^2"}}))
        rows.append((f"flywheel on the {shaft} shaft vs its inertia added", "speed [rad/s]", speed_error(fly, plain)))
    rim = scene(flywheel={"density": "7200 kg/m^3", "outer_diameter": "80 cm", "inner_diameter": "60 cm",
                          "width": "12 cm"}).flywheel.moment_of_inertia
    formula = math.pi * 7200 * 0.12 * (0.4**4 - 0.3**4) / 2
    rows.append(("rim inertia vs the formula", "relative", abs(rim - formula) / formula))
    w0 = 300 * math.pi / 30
    table = [[f"{float(w)!r} rad/s", f"{float(500 * (1 - w / w0))!r} N*m"] for w in np.linspace(0, w0, 7)]
    tabled = simulate(scene(motor={"stall_torque": None, "no_load_speed": None, "torque_speed": table}))
    rows.append(("torque-speed table on the line vs linear motor", "speed [rad/s]", speed_error(tabled, simulate(scene()))))
    w1, force = 30.0, 2000.0
    off = simulate(scene(motor={"stall_torque": None, "no_load_speed": None, "torque": "0 N*m"},
                         clutch={"engagement_force": f"{force} N"}, load={"mass": "0 kg"},
                         initial={"motor_speed": f"{w1} rad/s"}))
    ja, jb = 0.9, 40.0 / (90 / 17) ** 2
    torque = 0.1 * ConeClutch(0.20, 0.24, math.radians(25), 0.3, 0.1).torque_per_newton * force
    lock = ja * jb * w1 / (torque * (ja + jb))
    heat = ja * jb * w1**2 / (2 * (ja + jb))
    rows.append(("motor off: lock-up time vs closed form", "relative", abs(off.lockup_time - lock) / lock))
    rows.append(("motor off: clutch heat vs closed form", "relative", abs(off.slip_energy - heat) / heat))
    from hoistsim.results.report import table as text_table

    print(text_table(["check (rtol 1e-10)", "error in", "largest error"], [[a, b, f"{c:.1e}"] for a, b, c in rows]))


if __name__ == "__main__":
    main()

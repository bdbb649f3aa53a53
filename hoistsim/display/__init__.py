"""What each kind of part shows: the panels, phases, summary panels and headline the figures and tables
draw of it, as plain data (:mod:`.panel`), one module a part; no JAX, no machine.

``DISPLAYS`` lists them in the order the figures merge their panels and the title says their headlines.
May import: the foundation.
"""

from __future__ import annotations

from .bearings import DRUM_SHAFT_LOADS
from .buffer import BUFFER
from .clutch_heating import CLUTCH_HEATING
from .dc_machine import DC_MACHINE
from .eddy_current_brake import EDDY_CURRENT_BRAKE
from .end_stop import END_STOP
from .friction_brake import FRICTION_BRAKE
from .friction_clutch import FRICTION_CLUTCH
from .gear_pair import GEAR_PAIR
from .ground import GROUND
from .holding_brake import HOLDING_BRAKE
from .induction_machine import INDUCTION_MACHINE
from .linkage import LINKAGE
from .load import LOAD
from .mass import MASS
from .mesh_friction import MESH_FRICTION
from .motion_source import MOTION_SOURCE
from .motor import MOTOR
from .panel import Display as Display
from .part_names import under_part_names
from .periodic_regime import PERIODIC_REGIME
from .ratchet import RATCHET
from .rope import ROPE
from .shaft import SHAFT
from .shaft_torque import SHAFT_TORQUE
from .speed_controller import SPEED_CONTROLLER
from .spring_damper import SPRING_DAMPER
from .vehicle import VEHICLE

DISPLAYS: tuple[Display, ...] = (MOTOR, GEAR_PAIR, MESH_FRICTION, FRICTION_CLUTCH, CLUTCH_HEATING, LOAD, ROPE,
                                 GROUND, BUFFER, HOLDING_BRAKE, FRICTION_BRAKE, RATCHET, DRUM_SHAFT_LOADS, PERIODIC_REGIME,
                                 SHAFT, MASS, END_STOP, VEHICLE, SHAFT_TORQUE, MOTION_SOURCE, DC_MACHINE,
                                 INDUCTION_MACHINE, SPEED_CONTROLLER, LINKAGE, SPRING_DAMPER, EDDY_CURRENT_BRAKE)


def headline(summary: dict, names: dict | None = None) -> list[str]:
    """What each part of a run says of it in a few words (when the clutch locks, its heat, where the load
    went, the peak rope force), each part the run has; ``names``: the run's names table (its parts' names ->
    those its summary keeps them under, :mod:`.part_names`)."""
    summary = under_part_names(summary, names or {})
    said = []
    for display in DISPLAYS:
        if display.headline is None:
            continue
        try:
            text = display.headline(summary)
        except KeyError:  # a part the run has not
            continue
        if text:
            said.append(text)
    return said

"""A drawn drivetrain's masses on a line and the forces on them: their velocities, positions and forces."""

from __future__ import annotations

from .panel import Display, Panel, Trace, drawn_parts


def _panels_for(run: dict) -> tuple:
    masses = drawn_parts(run, "masses")
    if not masses:
        return ()
    forces = tuple(Trace(f"force{i + 1} on {entry['mass']}", f"force{i + 1}")
                   for i, entry in enumerate(drawn_parts(run, "forces")))
    return (Panel("mass_velocities", "velocity [m/s]", 1, tuple(Trace(name, f"{name}_velocity") for name in masses)),
            Panel("mass_positions", "position [m]\n(centres)", 2, tuple(Trace(name, f"{name}_position")
                                                                       for name in masses), height=0.8),
            *((Panel("mass_forces", "external force [N]", 5, forces, zero_line=True, height=0.8),) if forces else ()))


MASS = Display(panels_for=_panels_for, reads=lambda column: column.endswith(("_velocity", "_position"))
               or column.startswith("force"))

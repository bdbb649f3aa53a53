"""What the displays of a drawn drivetrain's electrical machines share: the torque each puts on its shaft
beside the external torques, a panel of their currents and one of their voltages."""

from __future__ import annotations

from .panel import Panel, Trace, drawn_parts


def machine_panels(run: dict, kind: str, current: str, voltage: str) -> tuple:
    """The panels of the machines of ``kind`` (drivetrain.<kind>) in ``run``, their currents' and voltages'
    panels labelled ``current`` and ``voltage`` (panels of one name from several kinds are one panel)."""
    machines = drawn_parts(run, kind)
    if not machines:
        return ()
    return (Panel("shaft_torques", "external torque [N*m]", 5,
                  tuple(Trace(f"{name} (air gap)", f"{name}_torque") for name in machines), zero_line=True,
                  height=0.8),
            Panel("machine_currents", current, 6, tuple(Trace(name, f"{name}_current") for name in machines),
                  zero_line=True, height=0.8),
            Panel("machine_voltages", voltage, 7, tuple(Trace(name, f"{name}_voltage") for name in machines),
                  height=0.8))


def reads_machine_column(column: str) -> bool:
    return column.endswith(("_current", "_voltage", "_torque"))

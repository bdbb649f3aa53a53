"""A drawn drivetrain's friction couplings (clutches, one-way clutches, bearing frictions): a panel of each one's
torque, one of every one's slip."""

from __future__ import annotations

from .panel import Display, Panel, Trace


def _headline(summary: dict) -> str | None:
    locks = [(key[: -len("_lockup_time")], float(value)) for key, value in summary.items()
             if key.endswith("_lockup_time")]
    if not locks:
        return None
    said = [f"{name} locks at {t:.4f} s" if t == t else f"{name} never locks" for name, t in locks]
    return ", ".join(said)


# the drivetrain's kinds of friction coupling, each drawn as a clutch: the torque it passes, its slip
KINDS = ("clutches", "one_way_clutches", "bearing_frictions")


def _panels_for(run: dict) -> tuple:
    """A panel per clutch: the torque it passes, and one panel of every clutch's slip, its locks marked."""
    drawn = run.get("parameters", {}).get("drivetrain") or {}
    clutches = [name for kind in KINDS for name in drawn.get(kind) or {}]
    panels = [Panel(f"{name}_torque", f"{name}\ntorque [N*m]", 20 + i, (Trace("torque", f"{name}_torque"),),
                    zero_line=True, height=0.8) for i, name in enumerate(clutches)]
    slips = tuple(Trace(name, f"{name}_slip", marks=("lock",), marks_of=name) for name in clutches)
    return (Panel("clutch_slips", "clutch slip [rad/s]", 10, slips, zero_line=True),) + tuple(panels) \
        if clutches else ()


FRICTION_CLUTCH = Display(headline=_headline, panels_for=_panels_for,
                          reads=lambda column: column.endswith(("_torque", "_slip", "_force")))

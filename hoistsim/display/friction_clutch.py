"""A drawn drivetrain's friction couplings (clutches, one-way clutches, bearing frictions): a panel of each one's
torque against its static capacity, one of every one's slip, one of every one's heat; each one's story in the
title."""

from __future__ import annotations

import numpy as np

from .panel import Display, Panel, Trace

# the drivetrain's kinds of friction coupling, each drawn as a clutch: the torque it passes, its slip, its heat
KINDS = ("clutches", "one_way_clutches", "bearing_frictions")
STORY_SWITCHES = 6  # a coupling that switches more often than this is told by its counts, not its instants
_SAID = {"engage": "engages", "lock": "locks", "unlock": "lets go", "disengage": "opens"}


def _names(summary: dict) -> list[str]:
    """The couplings a run's summary speaks of: a clutch's lock-up time, a bearing friction's slip duration and
    heat (``<name>_slip_energy``, a clutch's name for it)."""
    names = [key[: -len("_lockup_time")] for key in summary if key.endswith("_lockup_time")]
    return names + [key[: -len("_slip_duration")] for key in summary if key.endswith("_slip_duration")
                    and f"{key[: -len('_slip_duration')]}_slip_energy" in summary and key[: -len("_slip_duration")]
                    not in names]


def _times(count: int) -> str:
    return "once" if count == 1 else "twice" if count == 2 else f"{count} times"


def _heat(joules: float) -> str:
    return f"{joules:.3g} J of heat" if abs(joules) < 1000 else f"{joules / 1000:.3g} kJ of heat"


def _story(name: str, summary: dict) -> str:
    """What one coupling did: "clutch1 locks 0.791 s, lets go 0.831 s, ..., 29.5 J of heat"; from its switches
    (the run's events, where the summary holds them) or else its first lock."""
    lockup = float(summary.get(f"{name}_lockup_time", np.nan))
    heat = summary.get(f"{name}_slip_energy")
    events = summary.get("events")
    switches = [] if events is None else [(float(row["time"]), _text(row, "kind")) for row in events
                                          if _text(row, "element") == name and _text(row, "kind") in _SAID]
    held = [kind for _, kind in switches if kind in ("lock", "unlock")]
    # stuck at the first instant: its first lock is at 0, or its first switch of these two lets go
    from_start = lockup == 0 or (bool(held) and held[0] == "unlock")
    switches = [(t, kind) for t, kind in switches if not (kind == "lock" and t == 0)]
    said = ["locked from the start"] if from_start else []
    if events is None:  # the summary alone: its first lock
        said = said or ["never locks" if lockup != lockup else f"first locks at {lockup:.3f} s"]
    elif len(switches) > STORY_SWITCHES:  # how often, and when it first locks
        for word, said_as in _SAID.items():
            count = sum(kind == word for _, kind in switches)
            first = next((t for t, kind in switches if kind == word), None)
            if count:
                said.append(f"{said_as} {_times(count)}" + (f" (first {first:.3f} s)" if word == "lock" else ""))
    elif switches:
        said += [f"{_SAID[kind]} {t:.3f} s" for t, kind in switches]
    else:
        said += ["never slips"] if from_start else ["never locks"] if lockup != lockup else []
    if heat is not None and float(heat) > 0:
        said.append(_heat(float(heat)))
    return f"{name} " + ", ".join(said)


def _headline(summary: dict) -> str | None:
    names = _names(summary)
    return "; ".join(_story(name, summary) for name in names) if names else None


def _text(row, name: str) -> str:
    value = row[name]
    return value.decode() if isinstance(value, bytes) else str(value)


def _mirrored(name: str):
    """The capacity's other side (N*m), drawn only where the torque goes that way."""
    return lambda run: -run[f"{name}_capacity"] if (run[f"{name}_torque"] < 0).any() else None


def _static_torque(spec: dict) -> float:
    """A bearing friction's static torque (N*m): peak times its friction torque at rest (a table's first row)."""
    torque = spec["torque"]
    return float(spec.get("peak", 1.0)) * float(torque[0][1] if isinstance(torque, (list, tuple)) else torque)


def _capacities(kind: str, name: str, spec: dict) -> tuple:
    """The lines a coupling's torque meets: a clutch's static capacity (its other side where the torque goes
    there), a one-way clutch's on the side its freewheel does not hold, a bearing friction's static torque."""
    both = ("torque", "capacity")
    if kind == "clutches":
        return (Trace("static capacity", f"{name}_capacity", style=":", limit=True),
                Trace("- static capacity", f"{name}_capacity", style=":", limit=True,
                      needs=tuple(f"{name}_{w}" for w in both), value=_mirrored(name)))
    if kind == "one_way_clutches":  # driving shaft a forwards past b, the freewheel holds any torque
        return (Trace("- static capacity", f"{name}_capacity", style=":", limit=True,
                      needs=tuple(f"{name}_{w}" for w in both), value=lambda run: -run[f"{name}_capacity"]),)
    static = _static_torque(spec)
    return (Trace("static torque", f"{name}_torque", style=":", limit=True,
                  value=lambda run: np.full(np.shape(run[f"{name}_torque"]), static)),
            Trace("- static torque", f"{name}_torque", style=":", limit=True,
                  value=lambda run: np.full(np.shape(run[f"{name}_torque"]), -static)
                  if (run[f"{name}_torque"] < 0).any() else None))


def _heat_panel(names: list[str], run: dict) -> Panel:
    """Every coupling's heat so far, in J or, where one passes a kJ, in kJ."""
    most = max((float(np.nanmax(run[f"{n}_energy"])) for n in names if f"{n}_energy" in run), default=0.0)
    kilo = most >= 1000
    return Panel("clutch_heats", f"clutch heat [{'kJ' if kilo else 'J'}]\n(so far)", 20 + len(names),
                 tuple(Trace(name, f"{name}_energy") for name in names), scale=1e-3 if kilo else 1.0, height=0.8)


def _panels_for(run: dict) -> tuple:
    """A panel of every coupling's slip, its locks marked; a panel per coupling: the torque it passes against its
    static capacity; a panel of every coupling's heat."""
    drawn = run.get("parameters", {}).get("drivetrain") or {}
    couplings = [(kind, name, spec) for kind in KINDS for name, spec in (drawn.get(kind) or {}).items()]
    if not couplings:
        return ()
    names = [name for _, name, _ in couplings]
    slips = tuple(Trace(name, f"{name}_slip", marks=("lock",), marks_of=name) for name in names)
    torques = tuple(Panel(f"{name}_torque", f"{name}\ntorque [N*m]", 20 + i,
                          (Trace("torque", f"{name}_torque"),) + _capacities(kind, name, spec),
                          zero_line=True, height=0.8) for i, (kind, name, spec) in enumerate(couplings))
    return (Panel("clutch_slips", "clutch slip [rad/s]", 10, slips, zero_line=True),) + torques \
        + (_heat_panel(names, run),)


def _reads(column: str) -> bool:
    # not the ledger's energy_<name>_energy: the heat is the coupling's own column
    return column.endswith(("_torque", "_slip", "_force", "_capacity", "_energy")) and not column.startswith(
        "energy_")


FRICTION_CLUTCH = Display(headline=_headline, panels_for=_panels_for, reads=_reads)

"""Every friction coupling (a hoist's cone clutch, a drawn drivetrain's clutches, one-way clutches and bearing
frictions), drawn alike under the names of the parts the run's scene has: a panel of every one's slip, a panel
each of the torque it passes against its static capacity, one of every one's heat; a lone coupling's open and
locked phases shaded; each one's story in the title; its lock-up time, heat and peak torque against a sweep's
value, the runs that never lock or never slip marked apart.

It reads a run's columns and summary under the parts' own names (``clutch_slip``, ``clutch_lockup_time``): the
figures put a hoist's in beside the names its file keeps (``slip_speed``, ``lockup_time``), and name the
couplings in ``run["parts"]`` (the drawn parts by kind, a hoist's as its template names them).
"""

from __future__ import annotations

import numpy as np

from .panel import RPM, Display, Outcome, Panel, Phase, SummaryPanel, Trace, on_line

# the drivetrain's kinds of friction coupling, each drawn as a clutch: the torque it passes, its slip, its heat
KINDS = ("clutches", "one_way_clutches", "bearing_frictions")
OPEN = 3  # a coupling's mode column while it is open (its force off)
STORY_SWITCHES = 6  # a coupling that switches more often than this is told by its counts, not its instants
_SAID = {"engage": "engages", "lock": "locks", "unlock": "lets go", "disengage": "opens"}
_LOCKED_COLOUR, _OPEN_COLOUR = "#1b7837", "0.3"


def couplings(run: dict) -> list[tuple[str, str, dict]]:
    """The run's friction couplings: (kind, name, its values), in the order the scene draws them."""
    parts = run.get("parts") or {}
    return [(kind, name, spec) for kind in KINDS for name, spec in (parts.get(kind) or {}).items()]


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
    return f"{joules:.3g} J of heat" if abs(joules) < 1000 else f"{joules / 1000:.2f} kJ of heat"


def _text(row, name: str) -> str:
    value = row[name]
    return value.decode() if isinstance(value, bytes) else str(value)


def _story(name: str, summary: dict) -> str:
    """What one coupling did: "clutch1 locks at 0.791 s, lets go 0.831 s, ..., 29.5 J of heat"; from its
    switches (the run's events, where the summary holds them) or else its first lock."""
    lockup = float(summary.get(f"{name}_lockup_time", np.nan))
    heat = summary.get(f"{name}_slip_energy")
    heat = None if heat is None or not float(heat) > 0 else float(heat)
    events = summary.get("events")
    switches = [] if events is None else [(float(row["time"]), _text(row, "kind")) for row in events
                                          if _text(row, "element") == name and _text(row, "kind") in _SAID]
    held = [kind for _, kind in switches if kind in ("lock", "unlock")]
    # stuck at the first instant: its first lock is at 0, or its first switch of these two lets go
    from_start = lockup == 0 or (bool(held) and held[0] == "unlock")
    switches = [(t, kind) for t, kind in switches if not (kind == "lock" and t == 0)]
    slipped = float(summary.get(f"{name}_slip_duration", 0.0)) > 0 or heat is not None
    if lockup != lockup and not switches:  # never held: its heat is the heat up to the end of the run
        return f"{name} never locks" + (f" ({_heat(heat)} up to the end)" if heat is not None else "")
    if events is None:  # the summary alone: its first lock
        said = ["locked from the start" if slipped else "never slips"] if from_start else \
            [f"first locks at {lockup:.3f} s"]
    elif not switches:  # held from the start to the end
        said = ["never slips"]
    elif len(switches) > STORY_SWITCHES:  # how often, and when it first locks
        said = ["locked from the start"] if from_start else []
        for word, said_as in _SAID.items():
            count = sum(kind == word for _, kind in switches)
            first = next((t for t, kind in switches if kind == word), None)
            if count:
                said.append(f"{said_as} {_times(count)}" + (f" (first at {first:.3f} s)" if word == "lock" else ""))
    else:
        said = (["locked from the start"] if from_start else []) + \
            [f"{_SAID[kind]} {'at ' if i == 0 else ''}{t:.3f} s" for i, (t, kind) in enumerate(switches)]
    if heat is not None:
        said.append(_heat(heat))
    return f"{name} " + ", ".join(said)


def _headline(summary: dict) -> str | None:
    names = _names(summary)
    return "; ".join(_story(name, summary) for name in names) if names else None


def _passed(name: str, on_line: bool) -> str:
    """The column of what a coupling passes: ``<name>_torque``, on a line ``<name>_friction``."""
    return f"{name}_{'friction' if on_line else 'torque'}"


def _mirrored(name: str, passed: str):
    """The capacity's other side, drawn only where the torque goes that way (a load running back)."""
    return lambda run: -run[f"{name}_capacity"] if (run[passed] < 0).any() else None


def _static_torque(spec: dict) -> float:
    """A bearing friction's static torque (N*m; on a line its static force, N): peak times its friction at rest (a
    table's first row, or a constant with its Stribeck curve's excess at rest)."""
    friction = spec["torque"] if spec.get("torque") is not None else spec["force"]
    at_rest = friction[0][1] if isinstance(friction, (list, tuple)) else friction + float(spec.get("stribeck") or 0.0)
    return float(spec.get("peak", 1.0)) * float(at_rest)


def _capacities(kind: str, name: str, spec: dict, passed: str) -> tuple:
    """The lines a coupling's torque (``passed``, its column) meets: a clutch's static capacity (its other side
    where the torque goes there), a one-way clutch's on the side its freewheel does not hold, a bearing
    friction's static torque."""
    both = ("torque", "capacity")
    if kind == "clutches":
        return (Trace("static capacity", f"{name}_capacity", style=":", limit=True),
                Trace("- static capacity", f"{name}_capacity", style=":", limit=True,
                      needs=(passed, f"{name}_capacity"), value=_mirrored(name, passed)))
    if kind == "one_way_clutches":  # driving shaft a forwards past b, the freewheel holds any torque
        return (Trace("- static capacity", f"{name}_capacity", style=":", limit=True,
                      needs=tuple(f"{name}_{w}" for w in both), value=lambda run: -run[f"{name}_capacity"]),)
    static, what = _static_torque(spec), "static force" if passed.endswith("_friction") else "static torque"
    return (Trace(what, passed, style=":", limit=True, value=lambda run: np.full(np.shape(run[passed]), static)),
            Trace(f"- {what}", passed, style=":", limit=True,
                  value=lambda run: np.full(np.shape(run[passed]), -static) if (run[passed] < 0).any() else None))


def _heat_panel(names: list[str], run: dict) -> tuple:
    """Every coupling's heat so far, in J or, where one passes a kJ, in kJ (drawn where none heats too: the runs
    of a sweep drawn beside this one may)."""
    most = max((float(np.nanmax(run[f"{n}_energy"])) for n in names if f"{n}_energy" in run), default=0.0)
    kilo = most >= 1000
    return Panel("clutch_heats", f"clutch heat [{'kJ' if kilo else 'J'}]\n(so far)", 22,
                 tuple(Trace(name, f"{name}_energy") for name in names), scale=1e-3 if kilo else 1.0, height=0.8),


def _panels_for(run: dict) -> tuple:
    """A panel of every coupling's slip, its locks marked; a panel per coupling: the torque it passes against its
    static capacity; a panel of every coupling's heat.  The slip in the units of the run's shaft speeds: a drawn
    drivetrain's in rad/s (Modelica's), a hoist's in rpm."""
    found = couplings(run)
    if not found:
        return ()
    names = [name for _, name, _ in found]
    lone = len(found) == 1
    rpm = not (run.get("parameters") or {}).get("drivetrain")
    line = [on_line(run, *(spec.get("between") or ())) for _, _, spec in found]  # a brake on a line: a force
    units = "m/s" if all(line) else "rpm" if rpm else "rad/s"
    slips = tuple(Trace(name, f"{name}_slip", marks=("lock",), marks_of=name) for name in names)
    slip = Panel("clutch_slips", f"clutch slip [{units}]\n(driving - driven half)", 10, slips,
                 scale=RPM if rpm else 1.0, zero_line=True)
    torques = tuple(Panel(passed, f"{name}{' ' if lone else chr(10)}{'friction [N]' if on else 'torque [N*m]'}", 20,
                          (Trace("transmitted", passed),) + _capacities(kind, name, spec, passed),
                          zero_line=True, height=1.0 if lone else 0.8)
                    for (kind, name, spec), on in zip(found, line) for passed in (_passed(name, on),))
    return (slip,) + torques + _heat_panel(names, run)


def _shading_for(run: dict) -> tuple:
    """A lone coupling's phases, shaded in every panel: open (its force off), locked.  Several couplings' would
    lie over one another: their locks are marked on their slips instead."""
    found = couplings(run)
    if len(found) != 1:
        return ()
    name = found[0][1]
    return (Phase(f"{name} open", f"{name}_mode", OPEN, _OPEN_COLOUR),
            Phase(f"{name} locked", f"{name}_locked", 1, _LOCKED_COLOUR))


def _summary_panels_for(summary: dict) -> tuple:
    """Each coupling's lock-up time, heat and peak torque against a sweep's value (a lone one's named as the
    hoist's clutch: "lock-up time"); the heat of a run that never locks is its heat up to the run's end."""
    names = _names(summary)
    said = (lambda name, what: what if len(names) == 1 else f"{name} {what}")
    return tuple(panel for name in names for panel in (
        SummaryPanel(f"{name}_lockup_time", said(name, "lock-up time") + " [s]", 0),
        SummaryPanel(f"{name}_slip_energy", f"{name} heat [kJ]", 1, scale=1e-3,
                     partial="heat up to the end of the run", partial_of=f"{name}_lockup_time"),
        SummaryPanel(f"{name}_peak_torque", f"peak {name} torque [N*m]", 2),
        SummaryPanel(f"{name}_peak_friction", f"peak {name} friction [N]", 2),
    ) if panel.name in summary)


def _outcomes_for(summary: dict) -> tuple:
    """The runs in which a coupling never locks, and those in which it never slips (held from the start)."""
    names = [name for name in _names(summary) if f"{name}_lockup_time" in summary]
    said = (lambda name, what: what if len(names) == 1 else f"{name} {what}")
    return tuple(outcome for name in names for outcome in (
        Outcome(said(name, "never locks"), lambda row, n=name: np.isnan(row[f"{n}_lockup_time"]), "#b2182b", "^"),
        Outcome(said(name, "never slips (locked from the start)"),
                lambda row, n=name: row[f"{n}_lockup_time"] == 0 and row.get(f"{n}_slip_duration", 0.0) == 0,
                _LOCKED_COLOUR, "D")))


def _reads(column: str) -> bool:
    # not the ledger's energy_<name>_energy: the heat is the coupling's own column
    return column.endswith(("_torque", "_friction", "_slip", "_force", "_capacity", "_energy", "_mode", "_locked")) \
        and not column.startswith("energy_")


FRICTION_CLUTCH = Display(headline=_headline, panels_for=_panels_for, reads=_reads, shading_for=_shading_for,
                          summary_panels_for=_summary_panels_for, outcomes_for=_outcomes_for)

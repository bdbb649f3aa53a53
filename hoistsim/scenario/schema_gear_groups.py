"""Shafts geared together: which turn as one body (at what speed over its first), and which a stage's teeth press
(the shafts on its output side) — read from a drawn drivetrain's gear stages.  A mass on a line geared to a shaft
(a rack on its pinion, a rope on its drum, a wheel rolling on the line) or to another mass (a lever; joined
rigidly at ratio 1) is one body with them as well, its velocity the shaft's speed times the stage's radius."""

from __future__ import annotations

import math

from ..errors import ScenarioError


def gear_groups(spec) -> dict:
    """Each shaft and mass of a drivetrain's ``spec`` (its keys) and its (root, speed over the root's): shafts
    and masses geared together turn as one body, the first of them in ``shafts`` (then ``masses``) its root.
    Gear stages that close a loop with ratios that disagree are refused, naming both (the machine could not
    turn)."""
    stages = {name: stage for name, stage in spec.gears.items() if stage.housing is None}  # on a housing: a linkage
    groups: dict = {}
    via: dict = {}  # shaft -> the stage that reached it
    for start in [*spec.shafts, *spec.masses]:
        if start in groups:
            continue
        groups[start] = (start, 1.0)
        reached = [start]
        while reached:
            shaft = reached.pop()
            _, ratio = groups[shaft]
            for name, stage in stages.items():
                a, b = stage.between
                if shaft not in (a, b):
                    continue
                other, other_ratio = (b, ratio / stage.ratio) if shaft == a else (a, ratio * stage.ratio)
                if other not in groups:
                    groups[other] = (start, other_ratio)
                    via[other] = name
                    reached.append(other)
                elif not math.isclose(groups[other][1], other_ratio, rel_tol=1e-12) and via.get(other) != name:
                    raise ScenarioError(f"drivetrain.gears.{name}.ratio", f"closes a loop with gears "
                                        f"{via.get(other, via.get(shaft))!r} whose ratios disagree: shaft "
                                        f"{other!r} would turn {groups[other][1]:.6g} and {other_ratio:.6g} times "
                                        f"as fast as {start!r} (the machine could not turn)")
    return groups


def beyond_stage(spec, name: str) -> tuple:
    """The shafts on a gear stage's output side: its output shaft first, then every shaft geared to it
    by other stages.  The tooth load is what these take; a stage in a loop of stages has no such side
    (its tooth load is not determined by the machine's motion): refused for a lossy one."""
    first, out = spec.gears[name].between
    reached, beyond = [out], [out]
    while reached:
        shaft = reached.pop()
        for other, stage in spec.gears.items():
            if other == name or shaft not in stage.between or stage.housing is not None:
                continue
            far = stage.between[1] if shaft == stage.between[0] else stage.between[0]
            if far == first:
                key = spec.gears[name].loss_key
                raise ScenarioError(f"drivetrain.gears.{name}.{key}", f"the stage is in a loop of gear "
                                    f"stages (through {other!r}): the torque its teeth pass is not determined, "
                                    f"give it no {key}")
            if far not in beyond:
                beyond.append(far)
                reached.append(far)
    return tuple(beyond)


def given_speed(spec, body: str) -> float | None:
    """A body's speed at the start as a drivetrain's ``spec`` gives it: a shaft's ``speed`` (rad/s) or a mass's
    ``velocity`` (m/s); None where it is left out."""
    part, key = (spec.shafts[body], "speed") if body in spec.shafts else (spec.masses[body], "velocity")
    return getattr(part, key) if key in part.model_fields_set else None


def speed_key(spec, body: str) -> str:
    """The key that gives a body's speed at the start: a shaft's ``speed``, a mass's ``velocity``."""
    return f"drivetrain.shafts.{body}.speed" if body in spec.shafts else f"drivetrain.masses.{body}.velocity"


def check_gear_sides(spec) -> None:
    """Each gear stage joins two shafts (a ratio or teeth), two masses (a ratio: a lever, 1 rigidly joined) or a
    shaft and a mass (a radius, the shaft first); ideal where it joins a mass (no losses, no housing)."""
    for name, stage in spec.gears.items():
        where = f"drivetrain.gears.{name}"
        for side in stage.between:
            if side not in spec.shafts and side not in spec.masses:
                raise ScenarioError(f"{where}.between", f"there is no shaft or mass {side!r} (shafts: "
                                    f"{', '.join(spec.shafts) or 'none'}; masses: {', '.join(spec.masses) or 'none'})")
        a, b = stage.between
        if a == b:
            raise ScenarioError(f"{where}.between", f"gears {a!r} to itself")
        masses = [side in spec.masses for side in stage.between]
        if stage.radius is not None and masses != [False, True]:
            raise ScenarioError(f"{where}.radius", "is a pinion's (a drum's, a wheel's) on its rack (rope, line): "
                                "give between [shaft, mass]; two shafts or two masses take a ratio")
        if stage.radius is None and masses[0] != masses[1]:
            raise ScenarioError(f"{where}.between", "joins a shaft to a mass: give the pinion's (the drum's, the "
                                "wheel's) radius, the shaft first, between [shaft, mass]")
        if any(masses):
            key = next((k for k in ("teeth", "housing", "loss_table", "efficiency", "backdrive_efficiency")
                        if getattr(stage, k) is not None), None)
            if key is not None:
                raise ScenarioError(f"{where}.{key}", "is a gear stage's between shafts: a stage that joins a mass "
                                    "is ideal, with a ratio or a radius")

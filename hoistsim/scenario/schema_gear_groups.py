"""Shafts geared together: which turn as one body (at what speed over its first), and which a stage's teeth press
(the shafts on its output side) — read from a drawn drivetrain's gear stages."""

from __future__ import annotations

import math

from ..errors import ScenarioError


def gear_groups(spec) -> dict:
    """Each shaft of a drivetrain's ``spec`` (its keys) and its (root, speed over the root's): shafts geared
    together turn as one body, the first
    of them in ``shafts`` its root.  Gear stages that close a loop with ratios that disagree are refused,
    naming both (the machine could not turn)."""
    stages = {name: stage for name, stage in spec.gears.items() if stage.housing is None}  # on a housing: a linkage
    groups: dict = {}
    via: dict = {}  # shaft -> the stage that reached it
    for start in spec.shafts:
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

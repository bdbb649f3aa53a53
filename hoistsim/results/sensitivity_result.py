"""A sensitivity's result: each summary's value and its derivative with respect to each key, with their units."""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..errors import ScenarioError


@dataclasses.dataclass
class Sensitivity:
    """Each summary's value and its derivative with respect to each key (SI units), a scenario's."""

    name: str
    keys: dict[str, float]  # key -> its value (SI)
    key_units: dict[str, str]
    values: dict[str, float]  # summary -> its value
    units: dict[str, str]  # summary -> its units
    derivatives: dict[str, dict[str, float]]  # summary -> key -> d summary / d key (SI); NaN: none exists
    tables: tuple[str, ...] = ()  # keys that hold a force table: their number is its largest force
    run: object = None  # with ``series``: the RunResult with each series' derivatives (d_<series>_d_<key>)

    def elasticity(self, summary: str, key: str) -> float:
        """(key / summary) * d summary / d key: the summary's relative change per relative change of the key."""
        value = self.values[summary]
        return self.keys[key] / value * self.derivatives[summary][key] if value else math.nan

    def derivative_units(self, summary: str, key: str) -> str:
        return units_over(self.units[summary], self.key_units[key])

    def to_dict(self) -> dict:
        """``{summary: {"value": v, "unit": "s", key: {"derivative": d, "elasticity": e, "unit": "s/kg"}}}``,
        SI: each summary's value (the table's) and unit beside its derivatives; None where none exists.  (A key
        is a scenario key, never named "value" or "unit".)"""
        def number(x: float):
            return x if math.isfinite(x) else None

        return {s: {"value": number(float(self.values[s])), "unit": self.units[s],
                    **{k: {"derivative": number(d), "elasticity": number(self.elasticity(s, k)),
                           "unit": self.derivative_units(s, k)}
                       for k, d in self.derivatives[s].items()}}
                for s in self.values}


def differentiable_summaries(summaries: dict[str, str], of: list[str] | None) -> list[str]:
    """The summaries ``of`` names (None: every one that is a number), each checked to be one of ``summaries``
    (name -> units) and a number."""
    numbers = [name for name, units in summaries.items() if units != "bool"]
    for name in of or ():
        if name not in summaries:
            raise ScenarioError("--of", f"no summary {name!r} in this scene; it has {', '.join(numbers)}")
        if summaries[name] == "bool":
            raise ScenarioError("--of", f"{name} is a yes/no: it has no derivative")
    return list(numbers if of is None else of)


def units_over(top: str, bottom: str) -> str:
    if bottom in ("", "1"):
        return top or "1"
    bottom = f"({bottom})" if any(c in bottom for c in "*/") else bottom
    return f"{top or '1'}/{bottom}"


def existing(values, derivatives):
    """The derivatives (a number or an array over runs), NaN where the summary itself is none (a lock-up that
    never comes) or the derivative is not finite (a switch that only grazes its threshold)."""
    return np.where(np.isfinite(values) & np.isfinite(derivatives), derivatives, np.nan)

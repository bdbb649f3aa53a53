"""A scenario's sweep: ``--sweep`` text, ranges, and each swept value validated alone.

A sweep of a million values cannot afford a whole scenario validated per
value: each value is validated as its field's type, on the validated base,
and the checks of the sections that hold it (and of the scenario) run again
on the copy (:func:`with_swept_value`).  Two swept keys have every
combination checked, for the checks across keys.  Errors name the sweep's key
and the value's position, as :mod:`hoistsim.scenario.loading` names keys.
"""

from __future__ import annotations

import functools
import json
import math
from typing import Annotated, Any

import numpy as np
from pydantic import BaseModel, TypeAdapter, ValidationError

from ..errors import ScenarioError
from . import swept_values
from . import units as u
from .keys import ALTERNATIVES, SWEEP_EXAMPLE, Where, assign, check_key, error_from, parse_override
from .schema import Scenario
from .yamlsource import copy_plain as _copy_plain
from .yamlsource import line_of


def check_sweep(scenario: Scenario, raw: dict, key: str, values: list, tree: Any,
                 source: str) -> tuple[np.ndarray, list]:
    """A sweep names a known key, and each of its values is one the key accepts (validated alone, on the
    validated base): the SI number of each value (NaN where it is not one, a table that varies), and each
    value as validated (what the key holds in that run: a sweep's runs are built from these)."""
    where = Where(f"sweep.{key}", source, tree, ("sweep", key))
    try:
        check_key(key, source, raw)
    except ScenarioError as exc:
        raise ScenarioError(f"sweep.{exc.key}", exc.message, source=source, line=where["line"]) from None
    if not isinstance(values, list) or not values:
        raise ScenarioError(message=f"needs a non-empty list of values, {SWEEP_EXAMPLE}", **where)
    base = {k: v for k, v in raw.items() if k != "sweep"}
    numbers = np.empty(len(values))

    def each_validated():
        for i, value in enumerate(values):
            try:
                run = with_swept_value(scenario, key, value, base)
            except ScenarioError as exc:
                detail = exc.message if exc.key in (key, "") else f"{exc.key}: {exc.message}"
                raise ScenarioError(f"sweep.{key}", f"value {i + 1} ({_format_value(value)}): {detail}",
                                    source=source, line=line_of(tree, ("sweep", key, i)) or where["line"]) from None
            numbers[i] = swept_number(run, key)
            yield held_at(run, key)

    return numbers, swept_values.collect(each_validated())  # as columns: a million runs' values in a few MB


def with_swept_value(scenario: Scenario, key: str, value: Any, raw: dict | None = None) -> Scenario:
    """The validated scenario with one key set to ``value``, validating the value alone.

    The value is validated as its field's type, then every check of the
    sections that hold it, and of the scenario, runs again on the copy: the
    same checks as validating the whole scenario, at a small part of the cost
    (a sweep of a million values validates each).  A key in a section the
    scenario lacks is validated with the whole scenario (``raw``, its plain
    data, needed then).
    """
    *path, leaf = key.split(".")
    models = [scenario]
    for part in path:
        models.append(_child(models[-1], part))
        if models[-1] is None:  # the sweep adds a section
            if raw is None:
                raw = {k: v for k, v in scenario.provenance.raw.items() if k != "sweep"}
            one = _copy_plain(raw)
            assign(one, key, value)
            try:
                return Scenario.model_validate(one)
            except ValidationError as exc:
                raise error_from(exc.errors()[0], None, "", set()) from None
    try:
        new = _field_adapter(type(models[-1]), leaf).validate_python(value)
    except ValidationError as exc:
        err = exc.errors()[0]
        raise error_from({**err, "loc": (*key.split("."), *err["loc"])}, None, "", set()) from None
    return _copied_with(models, key, new, check=True)


def with_validated_value(scenario: Scenario, key: str, value: Any) -> Scenario:
    """The scenario with one key set to a value validated already (as the file was read): copies, no checks."""
    models = [scenario]
    for part in key.split(".")[:-1]:
        models.append(_child(models[-1], part))
    return _copied_with(models, key, value, check=False)


def held_at(scenario: Scenario, key: str):
    """What a dotted key holds in a validated scenario, through sections, parts by name and lists' indices;
    None where something on its path is absent."""
    node = scenario
    for part in key.split("."):
        try:
            node = _child(node, part)
        except (AttributeError, KeyError, IndexError, ValueError):
            return None
        if node is None:
            return None
    return node


def _child(parent, part: str):
    """What ``part`` names in a section, or in sections by name (a dict) or in a list (by index)."""
    if isinstance(parent, dict):
        return parent[part]
    if isinstance(parent, (list, tuple)):
        return parent[int(part)]
    return getattr(parent, part)


def _with_child(parent, part: str, new, check: bool, where: str):
    """``parent`` (the section at ``where``) copied with what ``part`` names replaced by ``new`` (its checks
    run again if ``check``)."""
    if isinstance(parent, dict):
        return {**parent, part: new}
    if isinstance(parent, (list, tuple)):
        members = list(parent)
        members[int(part)] = new
        return type(parent)(members)
    copied = parent.model_copy(update={part: new})
    if check:
        _checked(copied, where)
    return copied


def _checked(section, where: str) -> None:
    """A section's checks across its keys, run again on a copy; a key a check names within the section
    (``.kinetic_friction``) is named from the top (``clutch.kinetic_friction``: the section is at ``where``)."""
    for validate in type(section).__pydantic_decorators__.model_validators.values():
        try:
            validate.func(section)  # each returns the model (a check before the values: given it, it passes it on)
        except ScenarioError as exc:
            if not exc.key.startswith("."):
                raise
            raise ScenarioError(where + exc.key, exc.message, source=exc.source, line=exc.line) from None


def _copied_with(models: list, key: str, new: Any, check: bool) -> Scenario:
    """``models`` (the scenario and each section on the key's path) copied with the key's leaf set to ``new``;
    ``check``: each copied section's checks across its keys run again."""
    *path, leaf = key.split(".")
    new = models[-1].model_copy(update={leaf: new, **{other: None for other in ALTERNATIVES.get(key, ())}})
    if check:
        _checked(new, ".".join(path))
    for depth in range(len(path), 0, -1):  # each holder, and the name it holds the section by
        new = _with_child(models[depth - 1], path[depth - 1], new, check, ".".join(path[:depth - 1]))
    return new


@functools.lru_cache(maxsize=None)
def _field_adapter(model: type[BaseModel], name: str) -> TypeAdapter:
    field = model.model_fields[name]
    return TypeAdapter(Annotated[(field.annotation, *field.metadata)] if field.metadata else field.annotation)


def swept_number(scenario: Scenario, key: str) -> float:
    """The SI value of a swept key in one run (a constant force table counts as its force; NaN if not a number)."""
    value = held_at(scenario, key)
    if hasattr(value, "forces"):
        return value.forces[0] if len(set(value.forces)) == 1 else math.nan
    return float(value) if isinstance(value, (int, float)) else math.nan


def expand_range(key: str, spec: Any, where: Where) -> tuple[Any, list[str]]:
    """``{from: 1000 N, to: 9000 N, count: 9}`` -> the evenly spaced values and their labels."""
    if not isinstance(spec, dict):
        return spec, [_format_value(v) for v in spec] if isinstance(spec, list) else []
    if set(spec) != {"from", "to", "count"}:
        raise ScenarioError(message=f"a range needs exactly from:, to: and count:, got {sorted(spec)}", **where)
    count = spec["count"]
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= 1_000_000:
        raise ScenarioError(message=f"count must be a whole number from 1 to 1000000, got {count!r}", **where)
    try:
        start, stop, unit = u.range_ends(spec["from"], spec["to"])
    except u.UnitError as exc:
        raise ScenarioError(message=f"range: {exc}", **where) from None
    step = (stop - start) / (count - 1) if count > 1 else 0.0
    values = [start + i * step for i in range(count - 1)] + [stop] if count > 1 else [start]
    labels = [f"{v:.6g} {unit}".rstrip() for v in values]
    if not unit:
        return values, labels
    # The ends stay as written (validated with their units, so a wrong dimension is
    # caught); the values between are SI numbers, which skips parsing each one.
    scale, offset = u.si_line(unit)
    return [spec["from"], *(v * scale + offset for v in values[1:-1]), spec["to"]][:count], labels


def parse_sweep(assignment: str) -> tuple[str, Any]:
    """``--sweep`` text -> (key, values): ``K=V1,V2,...``, ``K=[v1, v2]`` (YAML) or ``K=FROM:TO:COUNT``."""
    if "=" not in assignment:
        raise ScenarioError("--sweep", f"expected KEY=V1,V2,... or KEY=FROM:TO:COUNT, got {assignment!r}")
    key, text = (part.strip() for part in assignment.split("=", 1))
    check_key(key, "--sweep")
    if not text:
        raise ScenarioError(key, f"needs values, like {key}=V1,V2 or {key}=FROM:TO:COUNT", source="--sweep")
    if text.startswith("["):
        values = parse_override(f"{key}={text}")[1]
    elif text.count(":") == 1 and "," not in text:  # read as one value, pint would multiply the ends
        raise ScenarioError(key, f"a range is FROM:TO:COUNT, and {text!r} has no count: give how many values, "
                            f"like {key}={text.strip()}:9", source="--sweep")
    elif text.count(":") == 2:
        start, stop, count = (part.strip() for part in text.split(":"))
        if not count.isdigit():
            raise ScenarioError(key, f"the count in FROM:TO:COUNT must be a whole number, got {count!r}",
                                source="--sweep")
        return key, {"from": start, "to": stop, "count": int(count)}
    else:
        items = text.split(",")
        for i, item in enumerate(items):
            if not item.strip():  # said here, as --sweep's: read alone it would be --set's missing value
                raise ScenarioError(key, f"value {i + 1} of {len(items)} is empty in {text!r}: give "
                                    f"{key}=V1,V2,... with a value between every two commas", source="--sweep")
        values = [parse_override(f"{key}={item}")[1] for item in items]
    if not isinstance(values, list):
        values = [values]
    return key, values


# --------------------------------------------------------------------------------------
# sweeps


def _format_value(value: Any) -> str:
    if isinstance(value, list):
        return json.dumps(value, separators=(",", ":"), default=str)
    return str(value)

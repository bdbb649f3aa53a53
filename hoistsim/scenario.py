"""Scenario files: YAML -> a validated scenario in SI units.

Every problem with a scenario is raised as :class:`ScenarioError`, which names
the dotted key, the file and (where the YAML parser knows it) the line:
``FILE:LINE: dotted.key: message``.  The command line prints that one line and
exits with status 2.  Values are parsed and converted to SI in :mod:`.units`.
"""

from __future__ import annotations

import difflib
import io
import json
import typing
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ValidationError
from ruamel.yaml import YAML

from . import tables
from . import units as u
from .errors import ScenarioError as ScenarioError
from .schema import SOLVERS as SOLVERS  # noqa: F401  (part of this module's interface)
from .schema import Scenario as Scenario
from .schema import Section
from .tables import ForceTable as ForceTable  # noqa: F401  (part of this module's interface)
from .yamlsource import line_of as _line_of
from .yamlsource import read_yaml as _read_yaml
from .yamlsource import to_plain as _to_plain
from .yamlsource import yaml_reader as _yaml

# --------------------------------------------------------------------------------------
# keys: known paths, near matches, overrides


def _is_section(candidate) -> bool:
    return isinstance(candidate, type) and issubclass(candidate, Section)


def _model_of(section: type[BaseModel], name: str) -> type[Section] | None:
    """The section a key holds (None: a value, or sections by name or in a list: see ``_members_of``)."""
    field = section.model_fields.get(name)
    if field is None or _members_of(section, name) is not None:
        return None
    for candidate in (field.annotation, *getattr(field.annotation, "__args__", ())):
        if _is_section(candidate):
            return candidate
    return None


def _members_of(section: type[BaseModel], name: str) -> tuple[type, type[Section]] | None:
    """(dict or list, the section of each member) for a key that holds sections by name or in a list
    (a drivetrain's shafts, its torques), else None."""
    field = section.model_fields.get(name)
    annotation = getattr(field, "annotation", None)
    container = typing.get_origin(annotation)
    if container in (dict, list):
        member = typing.get_args(annotation)[-1]
        if _is_section(member):
            return container, member
    return None


def key_units(dotted: str) -> str:
    """The SI unit a scenario key is stored in ("" for a pure number, a table or an unknown key)."""
    model: type[BaseModel] | None = Scenario
    *sections, leaf = dotted.split(".")
    for part in sections:
        model = _model_of(model, part) if model is not None else None
    field = model.model_fields.get(leaf) if model is not None else None
    dimension = u.dimension_of(field) if field is not None else None
    return dimension.si_unit if dimension is not None else ""


def _all_keys(model: type[BaseModel] = Scenario, prefix: str = "") -> list[str]:
    keys = []
    for name in model.model_fields:
        sub = _model_of(model, name)
        keys += _all_keys(sub, f"{prefix}{name}.") if sub else [] if name == "sweep" else [prefix + name]
    return keys


def _suggest(word: str, choices: list[str], prefix: str = "") -> str:
    near = difflib.get_close_matches(word, choices, n=1, cutoff=0.6)
    if near:
        return f" (did you mean {prefix + '.' if prefix else ''}{near[0]}?)"
    elsewhere = [k for k in _all_keys() if k.rsplit(".", 1)[-1] == word]
    if elsewhere:
        return f" here (did you mean {elsewhere[0]}?)"
    return f"; known keys{' in ' + prefix if prefix else ''}: {', '.join(choices)}"


class _Where(Mapping):
    """key=, source= and line= of a ScenarioError (``**where``): the line is looked up only when an error
    is raised (finding it parses the file again, round-trip)."""

    def __init__(self, key: str, source: str, tree: Any, path: tuple):
        self.key, self.source, self.tree, self.path = key, source, tree, path

    def __iter__(self):
        return iter(("key", "source", "line"))

    def __len__(self) -> int:
        return 3

    def __getitem__(self, name):
        if name == "line":
            return _line_of(self.tree, self.path)
        return {"key": self.key, "source": self.source}[name]


def _check_tree(data: dict, model: type[BaseModel], path: tuple, tree: Any, source: str) -> None:
    """Unknown keys and sections that are not mappings, before any value is looked at."""
    for key, value in data.items():
        where = _Where(".".join(map(str, (*path, key))), source, tree, (*path, key))
        if key not in model.model_fields:
            known = list(model.model_fields)
            raise ScenarioError(message="unknown key" + _suggest(key, known, ".".join(map(str, path))), **where)
        if key == "sweep" and model is Scenario and not isinstance(value, dict):
            raise ScenarioError(message=f"must map keys to lists of values, {_SWEEP_EXAMPLE}", **where)
        members = _members_of(model, key)
        if members is not None:
            _check_members(value, *members, (*path, key), tree, source, where)
            continue
        sub = _model_of(model, key)
        if sub is None:
            continue
        if value is None:
            optional = "" if model.model_fields[key].is_required() else f", or remove {key}:"
            raise ScenarioError(message=f"the section is empty; give its keys ({', '.join(sub.model_fields)})"
                                f"{optional}", **where)
        if not isinstance(value, dict):
            raise ScenarioError(message=f"must be a section with its keys indented below it, got {value!r}",
                                **where)
        _check_tree(value, sub, (*path, key), tree, source)


def _check_members(value, container: type, member: type[BaseModel], path: tuple, tree: Any, source: str,
                   where) -> None:
    """Sections by name (a mapping) or in a list: each member's keys checked as a section's."""
    if container is dict and not isinstance(value, dict):
        raise ScenarioError(message=f"must map names to sections ({', '.join(member.model_fields)}), got {value!r}",
                            **where)
    if container is list and not isinstance(value, list):
        raise ScenarioError(message=f"must be a list of sections ({', '.join(member.model_fields)}), got {value!r}",
                            **where)
    named = value.items() if container is dict else enumerate(value)
    for name, entry in named:
        if not isinstance(entry, dict):
            raise ScenarioError(message=f"must be a section ({', '.join(member.model_fields)}), got {entry!r}",
                                **_Where(".".join(map(str, (*path, name))), source, tree, (*path, name)))
        _check_tree(entry, member, (*path, name), tree, source)


def bare_angles(data: dict, model: type[BaseModel], path: tuple, tree: Any, source: str) -> list[str]:
    """Warnings for angles, angular speeds and temperatures given as bare numbers (read as rad, rad/s, K).

    A bare 300 on no_load_speed is 300 rad/s, 2865 rpm: accepted (SI is the
    rule), but said, with the key and where it is.
    """
    notes = []
    for key, value in data.items():
        field = model.model_fields.get(key)
        sub = _model_of(model, key)
        if field is None:
            continue
        if sub is not None and isinstance(value, dict):
            notes += bare_angles(value, sub, (*path, key), tree, source)
            continue
        dimension = u.dimension_of(field)
        note = u.bare_number_note(value, dimension) if dimension is not None else None
        column = tables.first_column_of(field)
        if column is not None and isinstance(value, list):  # a table's first column: the first bare entry
            firsts = [row[0] for row in value if isinstance(row, list) and row]
            note = next((f"row {i + 1}: {n}" for i, n in enumerate(u.bare_number_note(x, column) for x in firsts)
                         if n), None)
        if note:
            line = _line_of(tree, (*path, key))
            notes.append(str(ScenarioError(".".join((*path, key)), note, source=source, line=line)))
    return notes


_SWEEP_EXAMPLE = ("like 'clutch.engagement_force: [1000 N, 2000 N]' or "
                  "'clutch.engagement_force: {from: 1000 N, to: 9000 N, count: 9}'")


def _check_key(dotted: str, origin: str, raw: dict | None = None) -> None:
    """Raise unless ``dotted`` names a scalar (or table) key of the schema (and, given the scenario's
    ``raw`` data, a member it has where the key names one: a clutch by its name, a torque by its index)."""
    model: type[BaseModel] = Scenario
    parts = dotted.split(".")
    member = False  # the part names a member of sections by name or in a list (a clutch, a torque's index)
    node = raw
    for i, part in enumerate(parts):
        if member:
            if members[0] is list and not part.isdigit():
                raise ScenarioError(".".join(parts[: i + 1]), "is a list: name a member by its index, from 0",
                                    source=origin)
            if node is not None:
                have = list(node) if isinstance(node, dict) else [str(k) for k in range(len(node))]
                if part not in have:
                    raise ScenarioError(".".join(parts[: i + 1]), f"there is no such member (there are: "
                                        f"{', '.join(have) or 'none'})", source=origin)
                node = node[part] if isinstance(node, dict) else node[int(part)]
            if i == len(parts) - 1:
                raise ScenarioError(dotted, "is a section; name one of its keys, e.g. "
                                    f"{dotted}.{next(iter(model.model_fields))}", source=origin)
            member = False
            continue
        if part == "sweep" and model is Scenario:
            what = "given with --set; edit the file's sweep: section" if origin == "--set" else "swept"
            raise ScenarioError("sweep", f"cannot be {what}", source=origin)
        if part not in model.model_fields:
            known = [k for k in model.model_fields if k != "sweep"]
            raise ScenarioError(".".join(parts[: i + 1]), "unknown key" + _suggest(part, known, ".".join(parts[:i])),
                                source=origin)
        members = _members_of(model, part)
        node = node.get(part) if isinstance(node, dict) else None
        if members is not None and i < len(parts) - 1:
            model, member = members[1], True
            node = node if isinstance(node, (dict, list)) else None if raw is None else {}
            continue
        sub = _model_of(model, part)
        if i == len(parts) - 1:
            if sub is not None or members is not None:
                raise ScenarioError(dotted, "is a section; name one of its keys, e.g. "
                                    f"{dotted}.{next(iter(sub.model_fields))}", source=origin)
            return
        if sub is None:
            raise ScenarioError(".".join(parts[: i + 1]), "is a value, not a section", source=origin)
        model = sub


def parse_override(assignment: str) -> tuple[str, Any]:
    """``"clutch.engagement_force=2500 N"`` -> (key, value); the value is read as YAML."""
    key, equals, text = assignment.partition("=")
    key = key.strip()
    if not equals or not key:
        raise ScenarioError("", f"expected KEY=VALUE, like clutch.engagement_force='2500 N', got {assignment!r}",
                            source="--set")
    try:
        value = _to_plain(_yaml().load(io.StringIO(text))) if text.strip() else None
    except Exception:  # not YAML: the text as written
        value = text.strip()
    if value is None:
        raise ScenarioError(key, f"needs a value, like {key}=<value>", source="--set")
    return key, value


# setting one way of giving a value (--set, sweep) drops the other way the file used
_ALTERNATIVES = {"motor.inertia": ("rotor_mass", "radius_of_gyration"),
                 "motor.rotor_mass": ("inertia",), "motor.radius_of_gyration": ("inertia",)}


def _assign(raw: dict, dotted: str, value: Any) -> None:
    node = raw
    parts = dotted.split(".")
    for part in parts[:-1]:
        if isinstance(node, list):  # a member of sections in a list, by its index
            node = node[int(part)]
            continue
        if not isinstance(node.get(part), (dict, list)):
            node[part] = {}
        node = node[part]
    node[int(parts[-1]) if isinstance(node, list) else parts[-1]] = value
    for other in _ALTERNATIVES.get(dotted, ()):
        node.pop(other, None)


# --------------------------------------------------------------------------------------
# loading


def load_scenario(source: str | Path, overrides: list[str] | dict[str, Any] | None = None,
                  sweeps: list[str] | None = None) -> Scenario:
    """Read and validate a scenario file, with optional ``dotted.key=value`` overrides."""
    path = Path(source)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ScenarioError("", "no such scenario file", source=str(source)) from None
    except IsADirectoryError:
        raise ScenarioError("", "is a folder, not a scenario file", source=str(source)) from None
    except UnicodeDecodeError:
        raise ScenarioError("", "not a text (UTF-8) file", source=str(source)) from None
    except OSError as exc:
        raise ScenarioError("", f"cannot read the scenario: {exc.strerror or exc}", source=str(source)) from None
    return scenario_from_text(text, source=str(source), overrides=overrides, sweeps=sweeps)


def scenario_from_text(text: str, source: str = "<scenario>",
                       overrides: list[str] | dict[str, Any] | None = None,
                       sweeps: list[str] | None = None) -> Scenario:
    """Validate scenario text; ``overrides`` set keys, ``sweeps`` (KEY=SPEC) replace the file's sweep."""
    tree = _read_yaml(text, source)
    try:
        raw = _to_plain(tree.data)
    except ScenarioError as exc:
        exc.source = source
        raise
    from .sweep_spec import _check_combinations, _check_sweep, _expand_range, parse_sweep

    if sweeps:
        raw["sweep"] = dict(parse_sweep(item) for item in sweeps)
        text = text.rstrip("\n") + "\n# sweep from the command line (replaces any sweep: above):\n" + "".join(
            f"#   --sweep {item}\n" for item in sweeps)
    pairs = list(overrides.items()) if isinstance(overrides, dict) else [
        parse_override(item) for item in (overrides or [])
    ]
    for key, value in pairs:
        _check_key(key, "--set", raw)
        _assign(raw, key, value)
    if pairs:
        text = text.rstrip("\n") + "\n# overrides from the command line:\n" + "".join(
            f"#   --set {k}={json.dumps(v, default=str)}\n" for k, v in pairs)
    _check_tree(raw, Scenario, (), tree, source)
    scenario = _validate(raw, tree, source, overridden={k for k, _ in pairs})
    scenario._overridden = {k for k, _ in pairs}
    for key, values in (scenario.sweep or {}).items():
        if key in scenario._overridden:
            raise ScenarioError(key, "is swept in the file (sweep:); --set cannot also set it", source="--set")
        # a sweep given on the command line has no line in the file
        where, lines = ("--sweep", None) if sweeps else (source, tree)
        values, labels = _expand_range(key, values, _Where(f"sweep.{key}", where, lines, ("sweep", key)))
        scenario._sweep_numbers[key], scenario._sweep_validated[key] = _check_sweep(scenario, raw, key, values,
                                                                                  lines, where)
        scenario._sweep_values[key] = values
        scenario._sweep_labels[key] = labels
    scenario._raw = raw
    scenario._text = text
    scenario._source = source
    scenario._warnings = bare_angles(raw, Scenario, (), tree, source)
    if len(scenario.sweep or ()) > 1:
        _check_combinations(scenario)
    return scenario


def scenario_from_dict(data: dict, name: str = "<dict>") -> Scenario:
    """Validate a scenario given as Python data (tests, notebooks)."""
    buffer = io.StringIO()
    YAML().dump(data, buffer)
    return scenario_from_text(buffer.getvalue(), source=name)


def _validate(raw: dict, tree: Any, source: str, overridden: set[str] = frozenset()) -> Scenario:
    try:
        return Scenario.model_validate(raw)
    except ValidationError as exc:
        raise _error_from(exc.errors()[0], tree, source, overridden) from None


def _error_from(err: dict, tree: Any, source: str, overridden: set[str]) -> ScenarioError:
    loc = tuple(err["loc"])
    kind, cause = err["type"], (err.get("ctx") or {}).get("error")
    if isinstance(cause, ScenarioError):  # a check across keys names its own key ...
        key = tuple(cause.key.lstrip(".").split("."))
        # ... from the top, or (".table") within a section that may sit at several places
        loc, message = (loc + key if cause.key.startswith(".") else key), cause.message
    elif kind == "missing":
        message = "required value is missing"
        if len(loc) == 1 and _model_of(Scenario, str(loc[0])) is not None:
            message = "required section is missing"
    elif kind == "literal_error":
        message = f"{err['msg'].replace('Input should be', 'must be')}, got {err['input']!r}"
    elif kind == "finite_number":
        message = f"must be a finite number, got {err['input']!r}"
    else:
        message = err["msg"].removeprefix("Value error, ")
    key = ".".join(str(p) for p in loc)
    if key in overridden:
        return ScenarioError(key, message, source="--set")
    row = (cause.row,) if isinstance(cause, tables.TableError) else ()
    return ScenarioError(key, message, source=source, line=_line_of(tree, (*loc, *row)))

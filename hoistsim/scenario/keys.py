"""A scenario's keys: the schema's paths, near matches for a mistyped one, where a key sits in its file.

What both reading a scenario (:mod:`.loading`) and its sweeps (:mod:`.sweep_spec`) need: a dotted key
checked against the schema (``check_key``), set in the raw data (``assign``), its unit
(``key_units``), and pydantic's first error turned into a one-line ScenarioError naming the key and
its line (``error_from``).
"""

from __future__ import annotations

import difflib
import io
import typing
from collections.abc import Mapping
from typing import Any

from pydantic import BaseModel

from ..errors import ScenarioError
from . import tables
from . import units as u
from .schema import Scenario, Section
from .yamlsource import line_of
from .yamlsource import to_plain as _to_plain
from .yamlsource import yaml_reader as _yaml


def _is_section(candidate) -> bool:
    return isinstance(candidate, type) and issubclass(candidate, Section)



def model_of(section: type[BaseModel], name: str) -> type[Section] | None:
    """The section a key holds (None: a value, or sections by name or in a list: see ``members_of``)."""
    field = section.model_fields.get(name)
    if field is None or members_of(section, name) is not None:
        return None
    for candidate in (field.annotation, *getattr(field.annotation, "__args__", ())):
        if _is_section(candidate):
            return candidate
    return None



def members_of(section: type[BaseModel], name: str) -> tuple[type, type[Section]] | None:
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



def field_at(dotted: str):
    """The schema field a dotted key names (a drawn part's through its name or index), or None."""
    model: type[BaseModel] | None = Scenario
    parts = dotted.split(".")
    i = 0
    while model is not None and i < len(parts) - 1:
        members = members_of(model, parts[i])
        model, i = (members[1], i + 2) if members is not None else (model_of(model, parts[i]), i + 1)
    return model.model_fields.get(parts[-1]) if model is not None and i == len(parts) - 1 else None


def key_units(dotted: str) -> str:
    """The SI unit a scenario key is stored in ("" for a pure number, a table or an unknown key)."""
    field = field_at(dotted)
    dimension = u.dimension_of(field) if field is not None else None
    return dimension.si_unit if dimension is not None else ""



def _all_keys(model: type[BaseModel] = Scenario, prefix: str = "") -> list[str]:
    keys = []
    for name in model.model_fields:
        sub = model_of(model, name)
        keys += _all_keys(sub, f"{prefix}{name}.") if sub else [] if name == "sweep" else [prefix + name]
    return keys



REFERENCE = "docs/scenario.md"  # the scenario reference, every key (from the repository's root; reference.py)
EVERY_KEY = f"; every key: {REFERENCE}"  # an unknown key's message ends with where every key is


def _suggest(word: str, choices: list[str], prefix: str = "") -> str:
    near = difflib.get_close_matches(word, choices, n=1, cutoff=0.6)
    if near:
        return f" (did you mean {prefix + '.' if prefix else ''}{near[0]}?)"
    elsewhere = [k for k in _all_keys() if k.rsplit(".", 1)[-1] == word]
    if elsewhere:
        return f" here (did you mean {elsewhere[0]}?)"
    return f"; known keys{' in ' + prefix if prefix else ''}: {', '.join(choices)}"



class Where(Mapping):
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
            return line_of(self.tree, self.path)
        return {"key": self.key, "source": self.source}[name]



def check_tree(data: dict, model: type[BaseModel], path: tuple, tree: Any, source: str) -> None:
    """Unknown keys and sections that are not mappings, before any value is looked at."""
    for key, value in data.items():
        where = Where(".".join(map(str, (*path, key))), source, tree, (*path, key))
        if key not in model.model_fields:
            known = list(model.model_fields)
            raise ScenarioError(message="unknown key" + _suggest(key, known, ".".join(map(str, path))) + EVERY_KEY,
                                **where)
        if key == "sweep" and model is Scenario and not isinstance(value, dict):
            raise ScenarioError(message=f"must map keys to lists of values, {SWEEP_EXAMPLE}", **where)
        members = members_of(model, key)
        if members is not None:
            _check_members(value, *members, (*path, key), tree, source, where)
            continue
        sub = model_of(model, key)
        if sub is None:
            continue
        if value is None:
            optional = "" if model.model_fields[key].is_required() else f", or remove {key}:"
            raise ScenarioError(message=f"the section is empty; give its keys ({', '.join(sub.model_fields)})"
                                f"{optional}", **where)
        if not isinstance(value, dict):
            raise ScenarioError(message=f"must be a section with its keys indented below it, got {value!r}",
                                **where)
        check_tree(value, sub, (*path, key), tree, source)



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
                                **Where(".".join(map(str, (*path, name))), source, tree, (*path, name)))
        check_tree(entry, member, (*path, name), tree, source)


SWEEP_EXAMPLE = ("like 'clutch.engagement_force: [1000 N, 2000 N]' or "
                  "'clutch.engagement_force: {from: 1000 N, to: 9000 N, count: 9}'")



def check_key(dotted: str, origin: str, raw: dict | None = None) -> None:
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
            raise ScenarioError(".".join(parts[: i + 1]), "unknown key" + _suggest(part, known, ".".join(parts[:i]))
                                + EVERY_KEY, source=origin)
        members = members_of(model, part)
        node = node.get(part) if isinstance(node, dict) else None
        if members is not None and i < len(parts) - 1:
            model, member = members[1], True
            node = node if isinstance(node, (dict, list)) else None if raw is None else {}
            continue
        sub = model_of(model, part)
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
ALTERNATIVES = {"motor.inertia": ("rotor_mass", "radius_of_gyration"),
                 "motor.rotor_mass": ("inertia",), "motor.radius_of_gyration": ("inertia",)}



def assign(raw: dict, dotted: str, value: Any) -> None:
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
    for other in ALTERNATIVES.get(dotted, ()):
        node.pop(other, None)



def error_from(err: dict, tree: Any, source: str, overridden: set[str]) -> ScenarioError:
    loc = tuple(err["loc"])
    kind, cause = err["type"], (err.get("ctx") or {}).get("error")
    if isinstance(cause, ScenarioError):  # a check across keys names its own key ...
        key = tuple(cause.key.lstrip(".").split("."))
        # ... from the top, or (".table") within a section that may sit at several places
        loc, message = (loc + key if cause.key.startswith(".") else key), cause.message
    elif kind == "missing":
        message = "required value is missing"
        if len(loc) == 1 and model_of(Scenario, str(loc[0])) is not None:
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
    return ScenarioError(key, message, source=source, line=line_of(tree, (*loc, *row)))

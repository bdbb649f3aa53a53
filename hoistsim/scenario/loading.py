"""Scenario files: YAML -> a validated scenario in SI units.

Every problem with a scenario is raised as :class:`ScenarioError`, which names
the dotted key, the file and (where the YAML parser knows it) the line:
``FILE:LINE: dotted.key: message``.  The command line prints that one line and
exits with status 2.  Values are parsed and converted to SI in :mod:`.units`.
"""

from __future__ import annotations

import io
import json
from pathlib import Path
from typing import Any

from pydantic import ValidationError
from ruamel.yaml import YAML

from ..errors import ScenarioError as ScenarioError
from .keys import Where, assign, check_key, check_tree, error_from, parse_override
from .provenance import Provenance, SweptKey
from .schema import SOLVERS as SOLVERS  # noqa: F401  (part of this module's interface)
from .schema import Scenario as Scenario
from .tables import ForceTable as ForceTable  # noqa: F401  (part of this module's interface)
from .value_notes import swept_notes, value_notes
from .yamlsource import read_yaml as _read_yaml
from .yamlsource import to_plain as _to_plain


# --------------------------------------------------------------------------------------
# loading


def load_scenario(source: str | Path, overrides: list[str] | dict[str, Any] | None = None,
                  sweeps: list[str] | None = None, strict: bool = False) -> Scenario:
    """Read and validate a scenario file, with optional ``dotted.key=value`` overrides; ``strict``: a value
    that may not say what was meant (a bare number on a length, a 40 m drum) is an error, not a warning (the
    error raised is the first, the others its ``also``)."""
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
    return scenario_from_text(text, source=str(source), overrides=overrides, sweeps=sweeps, strict=strict)


def scenario_from_text(text: str, source: str = "<scenario>",
                       overrides: list[str] | dict[str, Any] | None = None,
                       sweeps: list[str] | None = None, strict: bool = False) -> Scenario:
    """Validate scenario text; ``overrides`` set keys, ``sweeps`` (KEY=SPEC) replace the file's sweep;
    ``strict`` as for :func:`load_scenario`."""
    tree = _read_yaml(text, source)
    try:
        raw = _to_plain(tree.data)
    except ScenarioError as exc:
        exc.source = source
        raise
    from .sweep_runs import check_combinations
    from .sweep_spec import check_sweep, expand_range, parse_sweep

    if sweeps:
        raw["sweep"] = dict(parse_sweep(item) for item in sweeps)
        text = text.rstrip("\n") + "\n# sweep from the command line (replaces any sweep: above):\n" + "".join(
            f"#   --sweep {item}\n" for item in sweeps)
    pairs = list(overrides.items()) if isinstance(overrides, dict) else [
        parse_override(item) for item in (overrides or [])
    ]
    for key, value in pairs:
        check_key(key, "--set", raw)
        assign(raw, key, value)
    if pairs:
        text = text.rstrip("\n") + "\n# overrides from the command line:\n" + "".join(
            f"#   --set {k}={json.dumps(v, default=str)}\n" for k, v in pairs)
    check_tree(raw, Scenario, (), tree, source)
    overridden = frozenset(k for k, _ in pairs)
    scenario = _validate(raw, tree, source, overridden=overridden)
    swept, notes = {}, []
    for key, spec in (scenario.sweep or {}).items():
        if key in overridden:
            raise ScenarioError(key, "is swept in the file (sweep:); --set cannot also set it", source="--set")
        # a sweep given on the command line has no line in the file
        where, lines = ("--sweep", None) if sweeps else (source, tree)
        values, labels = expand_range(key, spec, Where(f"sweep.{key}", where, lines, ("sweep", key)))
        numbers, validated = check_sweep(scenario, raw, key, values, lines, where)
        swept[key] = SweptKey(values=values, labels=labels, numbers=numbers, validated=validated)
        notes += swept_notes(key, spec, numbers, lines, where)
    notes = value_notes(raw, tree, source, overridden) + notes
    if strict and notes:  # every one said at once: fixed one at a time, a file would take as many tries
        first, *others = [ScenarioError(note.key, f"{note.message} (an error under --strict)", source=note.source,
                                        line=note.line) for note in notes]
        first.also = tuple(others)
        raise first
    scenario = scenario.with_provenance(Provenance(text=text, source=source, raw=raw, overridden=overridden,
                                                   warnings=tuple(map(str, notes)), swept=swept))
    if len(scenario.sweep or ()) > 1:
        check_combinations(scenario)
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
        raise error_from(exc.errors()[0], tree, source, overridden) from None



"""Reading scenario YAML so that errors can point at a file's lines.

ruamel's round-trip loader keeps the line of every key and list item, rejects
duplicate keys and reads YAML 1.2 (so ``1e-8`` is a number).  Parser errors are
turned into one-line messages that say what to fix.  It is slow (about 0.6 ms
for each force table a sweep lists: seconds for a few thousand), so the data
is read by ruamel's safe loader, on its C parser, and the round-trip tree is
made only when a line is asked for (an error, a warning); anything the safe
loader refuses (a tag of the user's own, a duplicate key) is read round-trip
at once, which says what is wrong.
"""

from __future__ import annotations

import io
import re
from typing import Any

from ruamel.yaml import YAML
from ruamel.yaml.comments import CommentedMap, CommentedSeq
from ruamel.yaml.error import MarkedYAMLError

from ..errors import ScenarioError
from .listed_items import PlainItems, cut_long_lists


def yaml_reader() -> YAML:
    yaml = YAML(typ="rt")  # round-trip: keeps line numbers; YAML 1.2, so 1e-8 is a number
    yaml.allow_duplicate_keys = False
    return yaml


_YAML_PROBLEMS = {  # ruamel's wording -> what to fix
    "while parsing a flow sequence": "a '[' list is not closed",
    "while parsing a flow mapping": "a '{' mapping is not closed",
    "while scanning a quoted scalar": "a quoted string is not closed",
    "that cannot start any token": "a tab or other character that cannot start a value; indent with spaces",
    "mapping values are not allowed here": "unexpected ':' (check the indentation, or quote a value that holds ': ')",
    "expected <block end>": "the indentation is inconsistent",
    "found another document": "a scenario is a single YAML document (remove the '---')",
}


class Lines:
    """The scenario's data, and its round-trip tree (the line of every key and item), parsed when first used."""

    def __init__(self, text: str, source: str, data: Any, tree: CommentedMap | None = None):
        self.text, self.source, self.data, self._tree = text, source, data, tree

    @property
    def tree(self) -> CommentedMap:
        if self._tree is None:  # the round-trip parser is stricter (a tab the C parser lets pass): its error
            self._tree = _read_round_trip(self.text, self.source)
        return self._tree


def read_yaml(text: str, source: str) -> Lines:
    try:
        fast = YAML(typ="safe", pure=False)
        fast.allow_duplicate_keys = False
        data = _with_long_lists(text, fast) or fast.load(io.StringIO(text))
        if isinstance(data, dict):
            return Lines(text, source, data)
    except Exception:  # read it round-trip: that says what is wrong, with its line
        pass
    tree = _read_round_trip(text, source)
    return Lines(text, source, tree, tree)


def _with_long_lists(text: str, fast: YAML) -> dict | None:
    """The data, a sweep's long lists read as columns (:mod:`.listed_items`); None where there are none."""
    cut = cut_long_lists(text, lambda piece: fast.load(io.StringIO(piece)))
    if cut is None:
        return None
    data = fast.load(io.StringIO(cut[0]))
    sweep = data.get("sweep") if isinstance(data, dict) else None
    if not isinstance(sweep, dict) or any(sweep.get(key, 0) is not None for key in cut[1]):
        return None  # not where they were seen to be: YAML reads it all
    sweep.update(cut[1])
    return data


def _read_round_trip(text: str, source: str) -> CommentedMap:
    try:
        data = yaml_reader().load(io.StringIO(text))
    except MarkedYAMLError as exc:
        problem, context = (exc.problem or "").strip(), (exc.context or "").strip()
        mark = exc.problem_mark
        if context.startswith(("while parsing a flow", "while scanning a quoted")) and exc.context_mark:
            mark = exc.context_mark  # where the unclosed thing was opened
        line = mark.line + 1 if mark is not None else None
        message = next((fix for cue, fix in _YAML_PROBLEMS.items() if cue in problem or cue in context),
                       problem or context or "cannot parse")
        if "duplicate key" in problem:
            first = _first_definition(text, line)
            message = "duplicate key" + (f" (first given at line {first})" if first else "")
        raise ScenarioError(_key_at(text, line), f"malformed YAML: {message}", source=source, line=line) from None
    except Exception as exc:  # ruamel's other errors (e.g. reader errors on binary data)
        raise ScenarioError("", f"malformed YAML: {str(exc).splitlines()[0]}", source=source) from None
    if data is None:
        raise ScenarioError("", "the scenario is empty; it needs name:, motor:, clutch:, gears:, drum:, load: "
                            "and simulation:", source=source)
    if not isinstance(data, dict):
        raise ScenarioError("", "a scenario must be a mapping of sections (name:, motor:, clutch:, ...)",
                            source=source, line=1)
    return data


_KEY_LINE = re.compile(r"^([ \t]*)([A-Za-z_][\w.-]*)[ \t]*:(?:\s|$)")
_SECTION_LINE = re.compile(r"^[ \t]*[A-Za-z_][\w.-]*[ \t]*:[ \t]*(#.*)?$")


def _key_at(text: str, line: int | None) -> str:
    """The dotted key written on a line (by indentation), for errors the YAML parser has no path for."""
    lines = text.splitlines()
    if line is None or not 1 <= line <= len(lines) or not (m := _KEY_LINE.match(lines[line - 1])):
        return ""
    path, indent = [m.group(2)], len(m.group(1))
    for above in reversed(lines[: line - 1]):
        m = _KEY_LINE.match(above)
        if m and len(m.group(1)) < indent and _SECTION_LINE.match(above):  # "motor:", nothing after
            path.insert(0, m.group(2))
            indent = len(m.group(1))
    return ".".join(path)


def _first_definition(text: str, line: int | None) -> int | None:
    """For a duplicate key on ``line``: the line of the same key earlier in the same mapping."""
    lines = text.splitlines()
    if line is None or not 1 <= line <= len(lines) or not (m := _KEY_LINE.match(lines[line - 1])):
        return None
    for i in range(line - 2, -1, -1):
        other = _KEY_LINE.match(lines[i])
        if other and len(other.group(1)) < len(m.group(1)):
            return None  # left the mapping
        if other and other.groups() == m.groups():
            return i + 1
    return None


def line_of(node: Any, path: tuple) -> int | None:
    """Best line (1-based) for a location: the deepest node the path reaches."""
    if isinstance(node, Lines):
        node = node.tree
    line = None
    for part in path:
        if isinstance(node, CommentedMap):
            part = next((k for k in node if str(k) == str(part)), None)  # keys may be numbers in YAML
            if part is None:
                break
            pos = node.lc.key(part)
        elif isinstance(node, CommentedSeq) and isinstance(part, int) and 0 <= part < len(node):
            pos = node.lc.item(part)
        else:
            break
        line = pos[0] + 1 if pos else line
        node = node[part]
    return line


def to_plain(node: Any, budget: list[int] | None = None) -> Any:
    """ruamel's round-trip types -> plain dict, list, str, int, float, bool."""
    if type(node) is PlainItems:  # a sweep's long list, read as plain data
        return list(node)
    budget = [100_000] if budget is None else budget  # values left: aliases can nest exponentially
    budget[0] -= 1
    if budget[0] < 0:
        raise ScenarioError("", "malformed YAML: more than 100000 values (aliases that expand without end?)")
    if isinstance(node, dict):
        return {k if isinstance(k, str) else str(k): to_plain(v, budget) for k, v in node.items()}
    if isinstance(node, (list, tuple)):
        return [to_plain(v, budget) for v in node]
    if isinstance(node, bool) or type(node).__name__ == "ScalarBoolean":
        return bool(node)
    if type(node).__name__ == "TaggedScalar":  # "!!str 3 kg", "!foo 3", a lone "="
        tag = str(getattr(node.tag, "value", node.tag) or "")
        return node.value if tag.startswith("tag:yaml.org,2002:") else f"{tag} {node.value}"
    for kind in (int, float, str):
        if isinstance(node, kind):
            return kind(node)
    return node


def copy_plain(data: Any) -> Any:
    """A copy of plain YAML data (dicts, lists, scalars): much faster than deepcopy."""
    if isinstance(data, dict):
        return {k: copy_plain(v) for k, v in data.items()}
    if isinstance(data, list):
        return [copy_plain(v) for v in data]
    return data

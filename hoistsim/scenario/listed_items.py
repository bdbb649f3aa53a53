"""A sweep's long list of values read as one template and its numbers, not scalar by scalar.

A sweep written by a script lists thousands of values of one form, a line each
(``- [[0 s, 0 N], [0.5 s, 0 N], [0.6 s, 3000.000 N]]``).  YAML's loader builds
and resolves each of their scalars in Python: some 0.1 ms a table, most of the
cost of a listed sweep's run.  Here each item's line is split into its numbers
and the text around them.  Where every item of a list has the same text around
its numbers (its template) and the template is plain flow YAML (lists of plain
scalars, no quotes, mappings, tags, anchors or comments), the items are read
together as JSON made from the template (a C parser, every item at once), and
YAML reads the file with those lines left blank.  The items read so are checked
against YAML's own reading of the first, middle and last: on any difference, or
anything not of that form, the file is read by YAML alone.
"""

from __future__ import annotations

import json
import re
from typing import Any

# Lists shorter than this are read by YAML: the saving is in long lists.
LONG = 64

_NUMBER = re.compile(r"([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)")
_SWEEP = re.compile(r"sweep[ \t]*:[ \t]*(#.*)?$")
_KEY = re.compile(r"([ \t]+)([A-Za-z_][\w.\-]*)[ \t]*:[ \t]*(#.*)?$")
_ITEM = re.compile(r"([ \t]*)-[ \t]+(\S.*?)[ \t]*$")
# Template text outside what JSON made from plain flow YAML can say as YAML would.
_NOT_PLAIN = re.compile(r"""["'{}#\\:?\t]""")
_NOT_FIRST = "&*!|>%@`-"  # what a plain scalar may not start with (an alias, a tag, ...)


class PlainItems(list):
    """A long list read here: plain data already (lists, strings, numbers; no aliases to expand)."""


def cut_long_lists(text: str, load) -> tuple[str, dict[str, list]] | None:
    """``text`` with the item lines of each long list under ``sweep:`` left blank, and those lists read, by key;
    None where there is none (``load``: YAML's reading of a piece of text, for the check)."""
    lines = text.split("\n")
    start = next((i for i, line in enumerate(lines) if _SWEEP.match(line)), None)
    if start is None:
        return None
    cut, lists = list(lines), {}
    i = start + 1
    while i < len(lines):
        line = lines[i]
        if line.strip() and not line[0].isspace():  # the sweep's mapping ends
            break
        key = _KEY.match(line)
        run = _item_run(lines, i + 1, len(key.group(1))) if key else None
        if run is None:
            i += 1
            continue
        end, items = run
        values = _read_items(items, load)
        if values is not None:
            lists[key.group(2)] = PlainItems(values)
            cut[i + 1:end] = [""] * (end - i - 1)
        i = end
    return ("\n".join(cut), lists) if lists else None


def _item_run(lines: list[str], first: int, key_indent: int) -> tuple[int, list[str]] | None:
    """(the line after, the items' text) of a list of one-line items starting at ``first``, long enough and
    ending where the key's mapping goes on (or the file ends); else None."""
    items, indent, i = [], None, first
    while i < len(lines) and (item := _ITEM.match(lines[i])) and indent in (None, len(item.group(1))):
        indent = len(item.group(1))
        items.append(item.group(2))
        i += 1
    if len(items) < LONG or indent < key_indent:
        return None
    for line in lines[i:]:  # what follows: a key of the sweep, a section, or the end (nothing more of the list)
        body = line.strip()
        if not body or body.startswith("#"):
            continue
        if len(line) - len(line.lstrip()) > key_indent or body.startswith("-"):
            return None
        break
    return i, items


def _read_items(items: list[str], load) -> list | None:
    """The items as YAML reads them, read as JSON made from their one template; None where they have none."""
    template = _NUMBER.split(items[0])[0::2]
    if _NOT_PLAIN.search("".join(template)):
        return None
    pieces = _json_pieces(template)
    if pieces is None:
        return None
    texts = []
    for item in items:
        parts = _NUMBER.split(item)
        if parts[0::2] != template:
            return None
        numbers = parts[1::2]
        texts.append("".join(p + n for p, n in zip(pieces, numbers)) + pieces[-1])
    try:
        values = json.loads("[" + ",".join(texts) + "]")
    except ValueError:
        return None
    for k in {0, len(items) // 2, len(items) - 1}:
        if not _same(values[k], load(items[k])):
            return None
    return values


def _json_pieces(template: list[str]) -> list[str] | None:
    """The template's text as JSON pieces to put the numbers between: each scalar quoted unless it is a
    number alone; None where it is not lists of plain scalars."""
    marked = "\x00".join(template)  # \x00: where a number goes
    out, depth = [], 0
    for token in re.split(r"([\[\],])", marked):
        if token in ("[", "]", ","):
            depth += {"[": 1, "]": -1, ",": 0}[token]
            if depth < 0:
                return None
            out.append(token)
            continue
        scalar = token.strip()
        if not scalar:
            out.append("")  # around a bracket; an empty scalar ("[1, , 2]") fails as JSON
            continue
        if scalar[0] in _NOT_FIRST:
            return None
        if scalar == "\x00":
            out.append(scalar)
        else:  # a word, or a number with its unit: a string (checked against YAML's reading after)
            out.append('"' + scalar + '"')
    if depth:
        return None
    return "".join(out).split("\x00")


def _same(ours: Any, yamls: Any) -> bool:
    if isinstance(ours, list):
        return isinstance(yamls, list) and len(ours) == len(yamls) and all(map(_same, ours, yamls))
    return type(ours) is type(yamls) and ours == yamls

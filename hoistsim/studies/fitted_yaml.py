"""A fitted scenario written back: the scenario's own text, each fitted value put in place of the old one.

Only the fitted keys' lines change, every other byte stays as the user wrote
it (a YAML dump would reflow the description and break a force table
mid-row).  Where each value sits is read from the YAML parser's events, which
mark every value's first and last character in the text.  A fitted value is
written in the unit the file gave it (``20 cm`` stays in cm), with a comment
that says where it came from: the trace, the fit's RMS and the key's 95 %
interval.  A key the trace does not determine keeps its value, and says so.
A fitted key the file does not write (a default) is added under its section.
"""

from __future__ import annotations

import dataclasses
import math
import re

from ..errors import ScenarioError
from ..running.key_directions import value_to_set


@dataclasses.dataclass
class _Span:
    """A value's place in the text: its first character and one past its last; where it is a mapping's value,
    where that key begins."""

    start: int
    end: int
    flow: bool = False  # a collection written inline ([...], {...})
    kind: str = "scalar"  # scalar, map or seq
    key_start: int | None = None
    text: str = ""  # a scalar's value


def fitted_text(result) -> str:
    """The scenario's text with each fitted key of ``result`` (a :class:`hoistsim.studies.fit.FitResult`)
    set to its fitted value and commented (see the module's text)."""
    text = _without_fitted_overrides(result.scenario.provenance.text, result.keys)
    spans = _value_spans(text)
    edits = []  # (position, end, new text): replacements, and insertions (end None: a whole line at position)
    for key in result.keys:
        path = _path_in(spans, key)
        note = _comment(result, key)
        if path is None:
            if key not in result.undetermined:
                edits.append(_inserted(text, spans, key, _value_text(result, key, None), note))
            continue
        span = spans[path]
        value = text[span.start:span.end] if key in result.undetermined else _value_text(result, key, span)
        edits.append(_replaced(text, span, value, note))
    for start, end, new in sorted(edits, key=lambda edit: edit[0], reverse=True):
        text = text[:start] + new + text[end:]
    return text


# What the scenario's text says of its --set overrides, after the file's own lines (hoistsim.scenario.loading).
OVERRIDES_NOTE = "\n# overrides from the command line:\n"


def _without_fitted_overrides(text: str, keys: list[str]) -> str:
    """The scenario's text without the note of the overrides the fit replaced (a fitted key's value is the
    fit's, not the command line's); the note is kept for any other."""
    body, found, note = text.partition(OVERRIDES_NOTE)
    if not found:
        return text
    kept = [line for line in note.splitlines(keepends=True)
            if line.removeprefix("#   --set ").partition("=")[0] not in keys]
    return body + "\n" + (OVERRIDES_NOTE[1:] + "".join(kept) if kept else "")


def _comment(result, key: str) -> str:
    trace = result.trace
    rms = ", ".join(f"{name} {_shown(trace, name, value)}" for name, value in result.residual_rms.items())
    if key in result.undetermined:
        return f"# not determined by {trace.source}: left as it was"
    low, high = result.intervals[key]
    unit = result.key_units[key]
    interval = (f"{_number(low, result, key)} to {_number(high, result, key)}"
                + ("" if unit == "1" else f" {unit}"))
    doubt = "" if result.sound else "; not a sound fit (see its warnings)"
    return f"# fitted to {trace.source} (RMS {rms}): 95 % interval {interval}{doubt}"


def _shown(trace, name: str, value: float) -> str:
    return f"{float(trace.shown(name, value) - trace.shown(name, 0.0)):.3g} {trace.written[name]}"


def _digits(result, key: str) -> int:
    """Significant digits enough to show the value to a tenth of its standard error, six at least."""
    value, error = abs(result.values[key]), result.standard_errors[key]
    if not error or not value or not math.isfinite(error):
        return 6
    return max(6, min(15, 2 + math.ceil(math.log10(value / error))))


def _number(x: float, result, key: str) -> str:
    return f"{x:.{_digits(result, key)}g}"


def _value_text(result, key: str, span: _Span | None) -> str:
    """The fitted value as the file would write it: a force table's rows scaled, a quantity in the unit the
    file wrote it in (SI where it wrote none)."""
    value, unit = result.values[key], result.key_units[key]
    digits = _digits(result, key)
    if span is not None and span.kind == "seq":  # a force table: every force scaled as the fit scaled its largest
        rows = value_to_set(result.scenario, key, value)
        return "[" + ", ".join(f"[{t:.6g} s, {f:.{digits}g} N]" for t, f in rows) + "]"
    if unit == "1":
        return f"{value:.{digits}g}"
    written = re.match(r"\s*[-+0-9.eE]+\s*(\S.*?)\s*$", span.text) if span is not None else None
    if written:
        from ..scenario.units import registry

        try:
            return f"{registry().Quantity(value, unit).to(written.group(1)).magnitude:.{digits}g} {written.group(1)}"
        except Exception:  # pint's: a unit it reads otherwise than the scenario does; SI says it plainly
            pass
    return f"{value:.{digits}g} {unit}"


def _replaced(text: str, span: _Span, value: str, note: str) -> tuple[int, int, str]:
    """The edit that writes ``value`` over the span and ``note`` after it: at the end of its line where
    nothing but a comment follows it there (that comment replaced), else on a line of its own above the
    key's."""
    line_end = text.find("\n", span.end)
    line_end = len(text) if line_end < 0 else line_end
    rest = text[span.end:line_end]
    if not rest.strip() or rest.strip().startswith("#"):
        return span.start, line_end, f"{value}  {note}"
    at = span.key_start if span.key_start is not None else span.start
    line_start = text.rfind("\n", 0, at) + 1
    indent = re.match(r"[ ]*", text[line_start:]).group(0)
    return line_start, span.end, f"{indent}{note}\n{text[line_start:span.start]}{value}"


def _inserted(text: str, spans: dict, key: str, value: str, note: str) -> tuple[int, int, str]:
    """The edit that adds a key the file does not write, under the deepest of its sections that it does
    (each missing section a line of its own); refused where that section is written inline."""
    parts = key.split(".")
    depth = len(parts) - 1
    while depth > 0 and tuple(parts[:depth]) not in spans:
        depth -= 1
    parent = spans.get(tuple(parts[:depth])) if depth else None
    if (parent is not None and (parent.kind != "map" or parent.flow)) or (depth == 0 and spans.get(()) is None):
        raise ScenarioError("-o", f"{key}: the file writes no place for it that can take a line; write it in "
                                  "the scenario (any value) and fit again")
    children = [span.key_start for path, span in spans.items()
                if len(path) == depth + 1 and path[:depth] == tuple(parts[:depth]) and span.key_start is not None]
    first = min(children) if children else None
    indent = first - (text.rfind("\n", 0, first) + 1) if first is not None else 2 * depth
    end = spans[tuple(parts[:depth])].end if depth else len(text.rstrip())
    line_end = text.find("\n", end)
    at = len(text) if line_end < 0 else line_end + 1
    lines = [" " * (indent + 2 * k) + f"{part}:" for k, part in enumerate(parts[depth:-1])]
    lines.append(" " * (indent + 2 * (len(parts) - 1 - depth)) + f"{parts[-1]}: {value}  {note}")
    lead = "" if text[:at].endswith("\n") or not text else "\n"
    return at, at, lead + "\n".join(lines) + "\n"


def _path_in(spans: dict, key: str) -> tuple | None:
    """The path of ``key``'s value among the spans: a section's key by name, a list's item by its index or
    by its ``name``; None where the file does not write it."""
    path: tuple = ()
    for part in key.split("."):
        here = spans.get(path)
        if here is not None and here.kind == "seq":
            if part.isdigit():
                path += (int(part),)
            else:
                named = [p[-2] for p, span in spans.items() if len(p) == len(path) + 2 and p[:len(path)] == path
                         and p[-1] == "name" and span.text == part]
                if not named:
                    return None
                path += (named[0],)
        else:
            path += (part,)
        if path not in spans:
            return None
    return path


def _value_spans(text: str) -> dict[tuple, _Span]:
    """Every value of the YAML text by its path (mapping keys, list indices): where it is."""
    from ruamel.yaml import YAML

    spans: dict[tuple, _Span] = {}
    stack: list[dict] = []

    def place(event) -> tuple:
        """The path of the node ``event`` starts, and where its key began (a mapping's value)."""
        if not stack:
            return (), None
        frame = stack[-1]
        if frame["kind"] == "map":
            frame["expect_key"] = True
            return frame["path"] + (frame["key"],), frame["key_start"]
        frame["index"] += 1
        return frame["path"] + (frame["index"] - 1,), None

    def reached(end: int) -> None:
        if stack:
            stack[-1]["last"] = max(stack[-1]["last"], end)

    for event in YAML(typ="rt").parse(text):
        name = type(event).__name__
        if name in ("MappingEndEvent", "SequenceEndEvent"):
            frame = stack.pop()
            end = event.end_mark.index if frame["flow"] else frame["last"]
            spans[frame["path"]] = _Span(frame["start"], end, frame["flow"], frame["kind"], frame["key_start"])
            reached(end)
            continue
        if name not in ("ScalarEvent", "AliasEvent", "MappingStartEvent", "SequenceStartEvent"):
            continue
        if stack and stack[-1]["kind"] == "map" and stack[-1]["expect_key"]:
            stack[-1].update(key=getattr(event, "value", None), key_start=event.start_mark.index, expect_key=False)
            continue
        path, key_start = place(event)
        start = event.start_mark.index
        if name in ("ScalarEvent", "AliasEvent"):
            spans[path] = _Span(start, event.end_mark.index, key_start=key_start, text=getattr(event, "value", ""))
            reached(event.end_mark.index)
        else:
            stack.append(dict(kind="map" if name == "MappingStartEvent" else "seq", path=path, start=start,
                              flow=bool(event.flow_style), key_start=key_start, last=start, index=0, key=None,
                              expect_key=True))
    return spans

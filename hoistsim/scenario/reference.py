"""The scenario reference, ``docs/scenario.md``, written from the schema: every key of every section, its
value (unit, table, choices), default, range and meaning, so that the document cannot drift from the code.

Each section (a pydantic model of :mod:`.schema` and the modules it imports) gets a table, its keys in the
schema's order: the unit from a quantity's :class:`.units.Dimension`, the range from its :class:`.units.Limits`,
a count's from :class:`.units.Count`, a table's columns from :class:`.tables.Columns` (or its
:class:`.tables.FirstColumn`), choices from a ``Literal``, the ways of giving one thing from the section's
``alternatives``, the meaning from the field's description (or the section's docstring for a key that holds
sections).  A section met again (a ripple on the motor, then on the drum) points to its first table.

``python -m hoistsim.scenario.reference [PATH]`` writes it (default ``docs/scenario.md``); a test compares the
file with what this writes, and that every key of the schema has its row.
"""

from __future__ import annotations

import re
import sys
import types
import typing
from pathlib import Path
from typing import Literal

from pydantic import BaseModel

from . import tables
from . import units as u
from .plausible import Plausible
from .keys import REFERENCE
from .schema import Scenario
from .schema_base import Section
from .signals import TimeSignal

PATH = REFERENCE  # from the repository's root (where an unknown key's error points)
COMMAND = "python -m hoistsim.scenario.reference"
_HEADER = "| key | value | default | range | meaning |\n|---|---|---|---|---|"
_DRAWN = ("drivetrain",)  # top-level sections of a drawn machine
_RUN = ("simulation", "sweep")  # the run's, not the machine's


def anchor(heading: str) -> str:
    """The link target GitHub gives a heading: lower case, spaces to dashes, other punctuation dropped."""
    text = heading.lower().replace(" ", "-")
    return "".join(c for c in text if c.isalnum() or c in "-_")


def _members(annotation) -> list:
    """A field's types, a union (``X | None``) opened, None left out."""
    if typing.get_origin(annotation) in (typing.Union, types.UnionType):
        return [a for a in typing.get_args(annotation) if a is not type(None)]
    return [annotation]


def _section_of(field) -> tuple[str, type[Section]] | None:
    """("section" | "by name" | "list", its model) for a key holding sections, else None."""
    for member in _members(field.annotation):
        origin = typing.get_origin(member)
        if origin in (dict, list):
            inner = typing.get_args(member)[-1]
            if isinstance(inner, type) and issubclass(inner, Section):
                return ("by name" if origin is dict else "list"), inner
        if isinstance(member, type) and issubclass(member, Section):
            return "section", member
    return None


def _units(dimension: u.Dimension, plausible: Plausible | None = None) -> str:
    """What a key measures and a value of it: the dimension's example, or the key's own where the dimension's
    is no plausible value of it (a gear's module: `4 mm`, not `20 cm`)."""
    example = plausible.example(dimension) if plausible is not None else dimension.example
    return f"{dimension.name}, e.g. `{example.strip(chr(39))}`"


def _columns(field) -> str:
    columns = u.metadata_of(field, tables.Columns)
    if columns is not None:
        return "[[" + ", ".join(name for name, _ in columns.columns) + "], ...]"
    first = tables.first_column_of(field)
    return f"[[{first.name}, ...], ...]" if first is not None else "[[...], ...]"


def _plain_value(annotation, metadata: tuple = ()) -> str:
    """What a value of a type is, in words (no section); ``metadata``: pydantic's, of a field not a union."""
    if typing.get_origin(annotation) is Literal:
        return "one of " + ", ".join(f"`{choice}`" for choice in typing.get_args(annotation))
    meta = (*getattr(annotation, "__metadata__", ()), *metadata)
    count = next((m for m in meta if isinstance(m, u.Count)), None)
    dimension = next((m for m in meta if isinstance(m, u.Dimension)), None)
    plausible = next((m for m in meta if isinstance(m, Plausible)), None)
    base = typing.get_args(annotation)[0] if hasattr(annotation, "__metadata__") else annotation
    if count is not None:
        return f"whole number ({count.what})"
    if dimension is not None and base is TimeSignal:
        return f"[signal](#time-signals) of {dimension.name}"
    if dimension is not None and base is float:
        return _units(dimension, plausible)
    if typing.get_origin(base) is tuple and typing.get_args(base)[-1] is not Ellipsis:
        return "[" + ", ".join(_plain_value(a) for a in typing.get_args(base)) + "]"
    if base is str:
        return "text"
    if base is bool:
        return "`true` or `false`"
    if typing.get_origin(base) is dict:
        return "mapping"
    return getattr(base, "__name__", str(base))


def value_of(field) -> str:
    """The value column: a unit, a table's columns, choices, a section's link (filled in by the caller)."""
    if u.metadata_of(field, tables.Columns) is not None or tables.first_column_of(field) is not None:
        dimension = u.metadata_of(field, u.Dimension)
        table = f"table {_columns(field)}"
        return f"{_units(dimension)}, or a {table}" if dimension is not None else table
    members = _members(field.annotation)
    if len(members) == 1:
        return _plain_value(members[0], tuple(field.metadata))
    return " or ".join(_plain_value(member) for member in members)


def _shown(number: float, dimension: u.Dimension | None) -> str:
    """A number in the user's unit (absolute zero in K), powers of ten as 1e-8."""
    if dimension is None or not dimension.si_unit:
        text = f"{number:g}"
    elif dimension is u.TEMPERATURE and number == 0:
        text = "0 K"
    else:
        text = u.show(number, dimension)
    return re.sub(r"e([+-])0*(\d)", r"e\1\2", text).replace("e+", "e")


def default_of(field) -> str:
    """The default column: ``required``, ``—`` (absent: the meaning says), or the value in the user's units."""
    if field.is_required():
        return "required"
    value = field.default
    if value is None:
        return "—"
    if isinstance(value, bool):
        return f"`{str(value).lower()}`"
    if isinstance(value, str):
        return f"`{value}`" if value else '`""`'
    if isinstance(value, (list, dict)) and not value:
        return "none"
    if isinstance(value, TimeSignal):
        return _shown(value.values[0], u.metadata_of(field, u.Dimension))
    if isinstance(value, BaseModel):
        return "its defaults"
    if isinstance(value, float):
        return _shown(value, u.metadata_of(field, u.Dimension))
    return str(value)


def range_of(field) -> str:
    """The range column: the limits a quantity is held to, a count's least value."""
    count = u.metadata_of(field, u.Count)
    if count is not None:
        return f"≥ {count.minimum}"
    limits, dimension = u.metadata_of(field, u.Limits), u.metadata_of(field, u.Dimension)
    if limits is None:
        return ""
    bounds = [(">", limits.gt), ("≥", limits.ge), ("<", limits.lt), ("≤", limits.le)]
    text = ", ".join(f"{sign} {_shown(bound, dimension)}" for sign, bound in bounds if bound is not None)
    plausible = u.metadata_of(field, Plausible)
    if plausible is not None:  # outside it: a warning (an error under --strict)
        text += f"{'; ' if text else ''}plausible {plausible.low} to {plausible.high}"
    return text


def _first_line(text: str | None) -> str:
    """A docstring's first paragraph, or a description, on one line (Markdown's quotes for reST's; a ``<name>``
    outside quotes escaped, which a browser would take for a tag and drop)."""
    line = " ".join((text or "").strip().split("\n\n")[0].split()).replace("``", "`")
    parts = line.split("`")  # the even ones are outside code spans
    return "`".join(part if i % 2 else part.replace("<", "&lt;").replace(">", "&gt;") for i, part in enumerate(parts))


def _first_sentence(text: str | None) -> str:
    line = _first_line(text)
    return line.split(". ")[0].rstrip(".")


class _Writer:
    """The document, section by section: each model's first place gets its table, later places a link."""

    def __init__(self):
        self.lines: list[str] = []
        self.placed: dict[type, str] = {}  # model -> the heading of its table

    def section(self, heading: str, model: type[Section], kind: str, level: int) -> None:
        self.placed[model] = heading
        # <name> written as entities: raw, Markdown renderers other than GitHub's take it for an HTML tag and drop it
        shown = heading.replace("<", "&lt;").replace(">", "&gt;")
        self.lines += ["", f"{'#' * level} {shown}", ""]
        intro = _first_line(model.__doc__) if model.__doc__ and model.__doc__ != Section.__doc__ else ""
        if kind == "by name":
            intro += (" " if intro else "") + "Sections by name: each name (a word) names the part and its outputs."
        elif kind == "list":
            intro += (" " if intro else "") + "A list: each entry has these keys."
        if intro:
            self.lines += [intro, ""]
        self.lines.append(_HEADER)
        later = []
        for name, field in model.model_fields.items():
            if field.exclude:  # a part's name: its key in the drivetrain, never written
                continue
            inner = _section_of(field)
            meaning = _first_line(field.description)
            if inner is not None:
                how, sub = inner
                path = f"{heading}.{name}" + {"section": "", "by name": ".<name>", "list": "[]"}[how]
                if sub not in self.placed and sub not in [s for _, s, _ in later]:
                    later.append((path, sub, how))
                    target = path
                else:
                    target = self.placed.get(sub) or next(p for p, s, _ in later if s is sub)
                what = {"section": "section", "by name": "sections by name", "list": "list of sections"}[how]
                value = f"{what}: [keys of `{target}`](#{anchor(target)})"
                meaning = meaning or _first_sentence(sub.__doc__)
            else:
                value = value_of(field)
            self.lines.append(f"| `{name}` | {value} | {default_of(field)} | {range_of(field)} | {meaning} |")
        self.alternatives(model)
        for path, sub, how in later:
            if sub not in self.placed:
                self.section(path, sub, how, min(level + 1, 4))

    def alternatives(self, model: type[Section]) -> None:
        """One line per group of ways to give one thing: ``Give one of: `a` + `b`, or `c`.``"""
        for group in model.alternatives:
            ways = ", or ".join(" + ".join(f"`{k.strip()}`" if " " not in k.strip() else k.strip()
                                           for k in way.split("+")) for way in group)
            self.lines += ["", f"Give one of: {ways}."]


_VALUES = """\
## Values

A value is an SI number or text with a unit, read by pint: `500 N*m`, `300 rpm`, `20 cm`, `200 daN`, `25 deg`,
`40 kg*m^2`, `2.4 kJ/K`, `25 degC`. Decimals take a point (`0.3`, never `0,3`); a product of units a `*` or a
space (`N*m` or `N m`: pint reads `Nm` as another unit), a power a `^` (`mm^2`). A bare number is SI (lengths in
metres, angles in radians, speeds in rad/s, temperatures in kelvin): it is accepted on a key with a unit with a
warning naming the key, its line and how the number was read (`drum: diameter: 40` is a 40 m drum). A value far
outside what its part measures (the range column's "plausible": a 40 m drum, a wire rope of 0.04 mm^2) is
accepted with a warning too. `--strict` (on `run`, `watch`, `check`, `statics`, `flywheel`) makes each of those
warnings an error, every one said at once, exit status 2. Zero is zero in any unit: it is never warned of. The
value column names what a key measures and an example; any unit of that kind is accepted.

| measures | SI unit (a bare number) | e.g. |
|---|---|---|
{dimensions}

**Tables** are rows in brackets, `[[0 rpm, 500 N*m], [300 rpm, 0 N*m]]`, their first column rising;
piecewise linear between rows, held beyond the ends. A table of time may repeat a time once: a step.

### What compiles

A scene's solver is compiled for its structure, once (the first run of a structure compiles for a few seconds,
and says so; later runs, in any process, load it from `~/.cache/hoistsim`). A new value of any key compiles
nothing: forces, masses, frictions, tolerances, `simulation.max_switches`, a table's values. What changes the
structure, and so compiles once more:
- a section or a part added, removed or renamed (a drawn part's name names its outputs);
- the number of rows of a table (a constant is a table of one row), or of a signal's harmonics;
- `simulation.solver`;
- the number of output rows past a power of two (`duration` / `output_interval`: 2049 to 4096 rows share one
  program, as do 4097 to 8192);
- a run that logs more events than its log has room for (some 200 switches a coupling), or takes more steps
  than it keeps room for to write its rows (a step an output row; in a sweep, one for every four), is run
  again, once, with room for them all.

A sweep pays for each structure once, whatever its values.

### Time signals

A drawn drivetrain's torques and forces are signals of time, given in one of three forms:
- a constant, `10 N*m`;
- a table `[[time, value], ...]`, piecewise linear, a repeated time a step, held beyond its ends;
- `{{offset: value, harmonics: [{{amplitude, frequency, phase}}, ...], envelope: [[time, factor], ...]}}`: the
  offset plus each amplitude sin(2 pi frequency t + phase) (frequency in Hz, phase default 0), their sum
  times the envelope where one is given (a sine switched off at 0.5 s: `[[0 s, 1], [0.5 s, 1], [0.5 s, 0]]`).
"""


def _dimensions() -> list[u.Dimension]:
    """Every dimension a key of the schema measures, in the order first met."""
    found: list[u.Dimension] = []

    def visit(model, seen):
        for field in model.model_fields.values():
            for meta in (u.metadata_of(field, u.Dimension), *(d for _, d in getattr(
                    u.metadata_of(field, tables.Columns), "columns", ()))):
                if meta is not None and meta not in found:
                    found.append(meta)
            inner = _section_of(field)
            if inner is not None and inner[1] not in seen:
                seen.add(inner[1])
                visit(inner[1], seen)

    visit(Scenario, {Scenario})
    return found


def reference() -> str:
    """The reference's text (Markdown)."""
    dimensions = "\n".join(f"| {d.name} | {d.si_unit or '(none)'} | `{d.example.strip(chr(39))}` |"
                           for d in _dimensions())
    writer = _Writer()
    writer.lines += [
        "# Scenario reference", "",
        f"Every key of a scenario file, written from the schema (`hoistsim/scenario/schema*.py`) by `{COMMAND}`: "
        "do not edit it by hand (a test compares it with the schema). A scenario draws the hoist by its sections "
        "(motor, clutch, gears, drum, load, and the optional parts), or a machine as a drivetrain "
        "(`drivetrain:`), never both; then the run (`simulation:`) and an optional `sweep:`.", "",
        _VALUES.format(dimensions=dimensions)]
    names = list(Scenario.model_fields)
    groups = (("The hoist", [n for n in names if n not in _DRAWN + _RUN]), ("A drawn drivetrain", list(_DRAWN)),
              ("The run", list(_RUN)))
    writer.lines += ["## The scenario's top keys", "", _HEADER]
    for name, field in Scenario.model_fields.items():
        value = f"section: [keys of `{name}`](#{anchor(name)})" if _section_of(field) else value_of(field)
        if name == "sweep":
            value = f"mapping: [a sweep](#{anchor('sweep')})"
        writer.lines.append(f"| `{name}` | {value} | {default_of(field)} | {range_of(field)} | "
                            f"{_first_line(field.description)} |")
    writer.alternatives(Scenario)
    for title, names in groups:
        writer.lines += ["", f"## {title}"]
        for name in names:
            inner = _section_of(Scenario.model_fields[name])
            if inner is not None and inner[1] not in writer.placed:
                writer.section(name, inner[1], inner[0], 3)
    writer.lines += ["", "### sweep", "", _SWEEP]
    return "\n".join(writer.lines).lstrip("\n") + "\n"


_SWEEP = """\
One run per value of each key it names (two keys: every combination), each key dotted as in `--set`:
a list of values, `clutch.engagement_force: [1000 N, 2000 N, 3201 N]`, or a range,
`clutch.engagement_force: {from: 1000 N, to: 9000 N, count: 9}`."""


def main(argv: list[str] | None = None) -> None:
    """Write the reference to PATH (default docs/scenario.md)."""
    args = sys.argv[1:] if argv is None else argv
    Path(args[0] if args else PATH).write_text(reference(), encoding="utf-8")


if __name__ == "__main__":
    main()

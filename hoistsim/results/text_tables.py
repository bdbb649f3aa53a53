"""Plain-text tables within a width: aligned columns, wrapped at word boundaries (:func:`table`) or, where each
column is a number with a unit, stacked in blocks that each repeat the row's label (:func:`fitted_table`); and
prose lines within the same width (:func:`note`)."""

from __future__ import annotations

import re
import textwrap


def table(headers: list[str], rows: list[list[str]], align: str | None = None, width: int | None = None) -> str:
    """A plain-text table; ``align`` has one 'l' or 'r' per column (default: first left, rest right).

    Within ``width`` characters (None: however wide) where its words allow: columns after the first (which
    names the row) narrowed (:func:`_narrowed`), their headers and cells wrapped at their spaces, a row on as
    many lines as its tallest cell; a header's lines sit on the rule."""
    align = align or "l" + "r" * (len(headers) - 1)
    widths = [max(len(str(x)) for x in col) for col in zip(headers, *rows)]
    if width is not None:
        widths = _narrowed(widths, [headers, *rows], align, width)

    def lines(cells, top: bool) -> list[str]:
        parts = [_words_within(str(c), w) for c, w in zip(cells, widths)]
        tall = max(len(p) for p in parts)
        parts = [p + [""] * (tall - len(p)) if top else [""] * (tall - len(p)) + p for p in parts]
        return ["  ".join(p[k].ljust(w) if a == "l" else p[k].rjust(w)
                          for p, w, a in zip(parts, widths, align)).rstrip() for k in range(tall)]

    rule = "  ".join("-" * w for w in widths)
    return "\n".join([*lines(headers, top=False), rule, *(line for r in rows for line in lines(r, top=True))])


def _narrowed(widths: list[int], lines: list[list], align: str, width: int) -> list[int]:
    """Column widths whose sum (with two spaces between) is at most ``width`` where the words allow, the first
    column (the row's name) kept whole and no column narrower than its longest word.  Narrowed a character at a
    time, the widest first, in the order that costs least: a header wider than its cells (wrapped over them),
    then the prose (the left-aligned columns, and values of several words), then the rest."""
    header, cells = lines[0], lines[1:]

    def longest_word(texts) -> int:
        return max((len(word) for text in texts for word in str(text).split()), default=0)

    columns = range(1, len(widths))
    values = [max((len(str(row[i])) for row in cells), default=0) for i in range(len(widths))]
    floors = [longest_word([header[i], *(row[i] for row in cells)]) for i in range(len(widths))]
    stages = [{i: max(values[i], floors[i]) for i in columns},  # the header's words over the values
              {i: floors[i] for i in columns if align[i] == "l" or _worded(cells, i)},  # prose, and values in words
              {i: floors[i] for i in columns}]
    widths = list(widths)
    for stage in stages:
        while sum(widths) + 2 * (len(widths) - 1) > width:
            narrower = [i for i, floor in stage.items() if widths[i] > floor]
            if not narrower:
                break
            widths[max(narrower, key=lambda i: widths[i])] -= 1
    return widths


def _worded(cells, i: int) -> bool:
    """Whether column ``i`` holds a value of several words (a table's knots, "375 at 75, 250 at 150"): it wraps
    as prose does, beside the prose, rather than keeping its width while the prose beside it is squeezed."""
    return any(" " in str(row[i]) for row in cells)


def _words_within(text: str, width: int) -> list[str]:
    """``text`` on lines of at most ``width``, broken at its spaces (a word longer than that on a line of its
    own, whole)."""
    if len(text) <= width:
        return [text]
    return textwrap.wrap(text, width, break_long_words=False, break_on_hyphens=False) or [""]


def note(text: str, width: int | None) -> str:
    """A line of prose within ``width`` characters (None: one line), broken at its spaces; a note in brackets
    goes on under its bracket."""
    if width is None or len(text) <= width:
        return text
    return "\n".join(textwrap.wrap(text, width, subsequent_indent=" " if text.startswith("(") else "",
                                   break_long_words=False, break_on_hyphens=False))


def fitted_table(headers: list[str], rows: list[list[str]], width: int | None = None, align: str | None = None,
                 keep: int = 1) -> str:
    """A table within ``width`` characters: each header "name [unit]" with its unit on a line of its own under the
    name, the name wrapped (:func:`_wrap`) where its column's values are narrower than it; the columns in blocks
    stacked one under the other, each block repeating the first ``keep`` columns (the row's label) and as many
    of the others as fit.  ``width`` None: one block however wide, the names unwrapped.  ``align`` as for
    :func:`table` (default: the kept columns left, the rest right)."""
    align = align or "l" * keep + "r" * (len(headers) - keep)
    name_lines, units, widths = column_layout(headers, rows, wrap=width is not None)
    blocks = _blocks(widths, keep, width)
    if len(blocks) > 1:  # as few blocks, evened out: the narrowest width that needs no more of them
        blocks = next((b for limit in range(sum(widths[:keep]), width + 1)
                       if len(b := _blocks(widths, keep, limit)) == len(blocks)), blocks)

    def line(cells, shown):
        return "  ".join(str(cells[i]).ljust(widths[i]) if align[i] == "l" else str(cells[i]).rjust(widths[i])
                         for i in shown).rstrip()

    texts = []
    for block in blocks:
        shown = [*range(keep), *block]
        tall = max(len(name_lines[i]) for i in shown)
        # the names' lines sit on the unit's line: a shorter name is padded above
        head = [line([([""] * (tall - len(lines)) + lines)[k] for lines in name_lines], shown) for k in range(tall)]
        head += [line(units, shown)] if any(units[i] for i in shown) else []
        texts.append("\n".join([*head, "  ".join("-" * widths[i] for i in shown), *(line(r, shown) for r in rows)]))
    return "\n\n".join(texts)


def column_layout(headers: list[str], rows: list[list[str]], wrap: bool = True):
    """Each column's name as lines (wrapped to its values' width unless not ``wrap``), its unit, its width."""
    names, units = zip(*(_name_and_unit(h) for h in headers))
    widths = [max(len(str(x)) for x in col) for col in zip(units, *rows)]
    name_lines = [_wrap(name, w) if wrap else [name] for name, w in zip(names, widths)]
    return name_lines, units, [max(w, *(len(line) for line in lines)) for w, lines in zip(widths, name_lines)]


def _wrap(name: str, width: int) -> list[str]:
    """A column's name on lines of at most ``width`` where it can be: broken after a space, an underscore or a dot
    (a summary's key, ``peak_clutch_`` over ``torque``), never inside a word."""
    lines = [""]
    for piece in re.split(r"(?<=[ _.])", name):
        if lines[-1] and len((lines[-1] + piece).rstrip()) > width:
            lines.append("")
        lines[-1] += piece
    return [line.rstrip() for line in lines]


def _blocks(widths: list[int], keep: int, width: int | None) -> list[list[int]]:
    """The columns after the first ``keep``, in order, as many to a block as fit ``width`` beside those."""
    blocks, block, used = [], [], sum(widths[:keep]) + 2 * (keep - 1)
    for i in range(keep, len(widths)):
        if block and width is not None and used + 2 + widths[i] > width:
            blocks.append(block)
            block, used = [], sum(widths[:keep]) + 2 * (keep - 1)
        block.append(i)
        used += 2 + widths[i]
    return [*blocks, block]


def _name_and_unit(header: str) -> tuple[str, str]:
    """"peak torque [N*m]" -> ("peak torque", "[N*m]"); a header without a unit keeps an empty one."""
    name, bracket, unit = header.partition(" [")
    return (name, f"[{unit}") if bracket and unit.endswith("]") else (header, "")

"""Every table a command prints fits the terminal's width (COLUMNS, or 100 characters when not a terminal), its
notes wrapped at their words and nothing left out: `check`, `statics`, `run` and `compare` (the whole table with
--wide, every value as CSV with --csv; `sensitivity`'s in tests/running/test_sensitivity.py).  `run` and
`compare` show a summary alike."""

from __future__ import annotations

import csv
import io
import os

import pytest
from click.testing import CliRunner
from helpers import EXERCISE6_FILE, ROOT, SCENARIOS

from hoistsim.cli import main
from hoistsim.cli.terminal import PIPED_WIDTH, table_width
from hoistsim.results.summary_display import SUMMARY_COLUMNS


def test_the_width_is_columns_or_the_terminal_or_a_default(monkeypatch):
    monkeypatch.setenv("COLUMNS", "80")
    assert table_width() == 80 and table_width(wide=True) is None
    monkeypatch.delenv("COLUMNS")

    def not_a_terminal(fd=None):
        raise OSError("not a terminal")

    monkeypatch.setattr(os, "get_terminal_size", not_a_terminal)
    assert table_width() == PIPED_WIDTH == 100


def _invoke(args, columns: int | None = None, code: int = 0):
    result = CliRunner(env={"COLUMNS": str(columns) if columns else None}).invoke(main, args)
    assert result.exit_code == code, result.output
    return result


def _words(text: str) -> list[str]:
    """Every word a table prints, its rules left out, in an order that wrapping cannot change."""
    return sorted(word for line in text.splitlines() if not line.startswith("--") for word in line.split())


@pytest.mark.parametrize("command", ["check", "statics"])
def test_what_check_and_statics_print_fits_80_columns_every_word_kept(command, monkeypatch):
    """Every shipped scenario's tables at COLUMNS=80 (`check` printed 114 characters, `statics` 110), their
    prose wrapped at its words: the same words as the table printed however wide."""
    monkeypatch.chdir(ROOT)  # "scenarios/NAME.yaml: valid (1 run)": a short line
    printed = 0
    for path in sorted(SCENARIOS.glob("*.yaml")):
        args = [command, f"scenarios/{path.name}"]
        fitted = CliRunner(env={"COLUMNS": "80"}).invoke(main, args)
        if command == "statics" and fitted.exit_code != 0:  # a drawn drivetrain: statics is the hoist's
            assert "drivetrain" in fitted.output, fitted.output
            continue
        assert fitted.exit_code == 0, fitted.output
        assert max(len(line) for line in fitted.stdout.splitlines()) <= 80, fitted.stdout
        assert _words(fitted.stdout) == _words(_invoke(args, columns=1000).stdout), path.name
        printed += 1
    assert printed >= 20


def _cells(text: str, label: str) -> list[str]:
    """Every cell of the rows labelled ``label``, block after block, the label left out."""
    return [cell for line in text.splitlines() if line.startswith(label + " ")
            for cell in line[len(label):].split()]


@pytest.mark.slow
def test_run_and_compare_fit_80_and_120_columns(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # "wrote run.h5 (...)": a short line
    label = "exercise6-direct-start"
    wide = _invoke(["run", str(EXERCISE6_FILE), "-o", "run.h5", "--wide"], columns=80).stdout
    whole = [line for line in wide.splitlines() if not line.startswith("wrote")]
    assert max(len(line) for line in whole) > 120 and "\n\n" not in wide  # one table, however wide
    assert "clutch heat" in whole[0] and "energy residual" in whole[0]
    values = _cells(wide, label)
    assert len(values) == 11 and values[:4] == ["0", "0", "0", "406.9"]
    for columns in (80, 120):
        text = _invoke(["run", str(EXERCISE6_FILE), "-o", "run.h5"], columns=columns).stdout
        lines = text.splitlines()
        assert max(len(line) for line in lines) <= columns, text
        assert _cells(text, label) == values  # every value, in order, block after block
        assert text.count("\n\n") == (1 if columns == 80 else 0)  # at 120 the names wrapped are enough
        assert lines[-1].startswith("wrote run.h5 (1 run")
        table = _invoke(["compare", "run.h5"], columns=columns).stdout
        assert max(len(line) for line in table.splitlines()) <= columns, table
        assert "--wide" in table.splitlines()[-1]
        # the file's summary compared, the run table's columns: that table (kJ, rpm, its headers)
        chosen = ",".join(["label", *(key for key, _, _ in SUMMARY_COLUMNS)])
        assert _invoke(["compare", "run.h5", "--columns", chosen], columns=columns).stdout == text[:text.index("wrote")]
    every = _invoke(["compare", "run.h5", "--wide"], columns=80).stdout
    assert "more column" not in every and "relative energy residual" in every.splitlines()[0]

    done = _invoke(["run", str(EXERCISE6_FILE), "-o", "run.h5", "--csv"], columns=80)
    rows = list(csv.reader(io.StringIO(done.stdout)))
    assert rows[:2] == list(csv.reader(io.StringIO(_invoke(["compare", "run.h5", "--csv"]).stdout)))[:2]
    assert rows[0][0] == "label" and rows[1][rows[0].index("lockup_time")] == "s" and len(rows) == 3
    assert rows[2][0] == label and float(rows[2][rows[0].index("lockup_time")]) == 0.0
    assert "wrote run.h5" in done.stderr and "wrote" not in done.stdout

"""`run` and `compare` print within the terminal's width (COLUMNS, or 100 characters when not a terminal); the
whole table with --wide, every value as CSV with --csv."""

from __future__ import annotations

import csv
import io
import os

import pytest
from click.testing import CliRunner
from helpers import EXERCISE6_FILE

from hoistsim.cli import main
from hoistsim.cli.terminal import PIPED_WIDTH, table_width


def test_the_width_is_columns_or_the_terminal_or_a_default(monkeypatch):
    monkeypatch.setenv("COLUMNS", "80")
    assert table_width() == 80 and table_width(wide=True) is None
    monkeypatch.delenv("COLUMNS")

    def not_a_terminal(fd=None):
        raise OSError("not a terminal")

    monkeypatch.setattr(os, "get_terminal_size", not_a_terminal)
    assert table_width() == PIPED_WIDTH == 100


def _invoke(args, columns: int | None = None):
    result = CliRunner(env={"COLUMNS": str(columns) if columns else None}).invoke(main, args)
    assert result.exit_code == 0, result.output
    return result


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
    every = _invoke(["compare", "run.h5", "--wide"], columns=80).stdout
    assert "more column" not in every and "energy_relative_residual" in every.splitlines()[0]

    done = _invoke(["run", str(EXERCISE6_FILE), "-o", "run.h5", "--csv"], columns=80)
    rows = list(csv.reader(io.StringIO(done.stdout)))
    assert rows[:2] == list(csv.reader(io.StringIO(_invoke(["compare", "run.h5", "--csv"]).stdout)))[:2]
    assert rows[0][0] == "label" and rows[1][rows[0].index("lockup_time")] == "s" and len(rows) == 3
    assert rows[2][0] == label and float(rows[2][rows[0].index("lockup_time")]) == 0.0
    assert "wrote run.h5" in done.stderr and "wrote" not in done.stdout

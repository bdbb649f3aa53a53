"""Every shipped scenario (``scenarios/*.yaml``, sweeps with every run) through ``hoistsim run`` to a file
that opens with rows, and its figures legible: tests/every_scene.py says what each is held to.  Most compile
a program of their own: all but the first scenario are slow."""

from __future__ import annotations

import pytest
from every_scene import files_in, runs_to_a_legible_file
from helpers import SCENARIOS


@pytest.mark.parametrize("name, path, text", files_in(SCENARIOS))
def test_the_scenario_runs_to_a_file_with_rows_and_legible_figures(name, path, text, tmp_path, monkeypatch):
    runs_to_a_legible_file(name, path, text, tmp_path, monkeypatch)

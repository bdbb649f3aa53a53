"""The property searches' own footing: a derandomized search draws the same scenes on every run of the same code,
whatever other test modules the process has imported before it (xdist hands a worker its files in no fixed
order)."""

from __future__ import annotations

import importlib

from helpers import property_settings
from hypothesis import given, settings
from hypothesis import strategies as st


def _drawn(pin: bool) -> list:
    seen = []

    @settings(max_examples=60, derandomize=True, database=None)
    @given(st.tuples(st.floats(0.1, 5.0), st.floats(-20.0, 20.0)))
    def probe(values):
        seen.append(values)

    if pin:
        property_settings(1, derandomize=True)
    probe()
    return seen


def test_a_derandomized_search_draws_the_same_scenes_whatever_modules_were_imported_before(tmp_path, monkeypatch):
    before = _drawn(pin=True)
    # a module full of numbers in the drawn ranges, as a test module of tables and found cases is
    (tmp_path / "numbers_in_range.py").write_text(
        "NUMBERS = (" + ", ".join(repr(0.1 + 0.0371 * i) for i in range(130)) + ")\n")
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.import_module("numbers_in_range")
    assert _drawn(pin=True) == before

"""What `hoistsim check` prints of a machine: each body in its own quantity, and an elastic rope's stiffness,
the load's static stretch on it and its natural frequency, against their closed forms."""

from __future__ import annotations

import math

import pytest
from click.testing import CliRunner
from helpers import SCENARIOS

from hoistsim.cli import main

ROPE_FILE = SCENARIOS / "brake_stop_on_an_elastic_rope.yaml"  # 500 kg on 20 m of wire rope, E 100 GPa, A 95 mm^2


def _rows(path) -> dict[str, list[str]]:
    """`check`'s symbol rows: symbol -> [quantity words..., value, unit] (a row a line: on a terminal as wide
    as its longest)."""
    result = CliRunner(env={"COLUMNS": "200"}).invoke(main, ["check", str(path)])
    assert result.exit_code == 0, result.output
    rows = {}
    for line in result.output.splitlines():
        cells = line.split()
        if len(cells) >= 3 and cells[-1] in ("kg", "kg*m^2", "kN/m", "mm", "rad/s", "Hz", "N*m", "m", "-"):
            rows[cells[0]] = cells
    return rows


def _value(rows, symbol: str, unit: str) -> float:
    assert rows[symbol][-1] == unit, rows[symbol]
    return float(rows[symbol][-2])


def _rope_numbers(k: float, mass: float, g: float = 9.81) -> dict[str, float]:
    """The closed forms: k in kN/m, m g / k in mm, sqrt(k / m) in rad/s and Hz."""
    omega = math.sqrt(k / mass)
    return {"k": k / 1e3, "s_st": mass * g / k * 1e3, "w_n": omega, "f_n": omega / (2 * math.pi)}


def test_a_wire_rope_its_stiffness_stretch_and_frequency():
    rows = _rows(ROPE_FILE)
    assert _value(rows, "m[load]", "kg") == 500.0  # a mass in kg, not an inertia
    assert "J[load]" not in rows and rows["J[motor]"][-1] == "kg*m^2"
    expected = _rope_numbers(100e9 * 95e-6 / 20.0, 500.0)  # E A / L = 475 kN/m
    assert expected["k"] == pytest.approx(475.0)
    for symbol, unit in (("k", "kN/m"), ("s_st", "mm"), ("w_n", "rad/s"), ("f_n", "Hz")):
        assert _value(rows, symbol, unit) == pytest.approx(expected[symbol], rel=5e-4), symbol
    assert _value(rows, "s_st", "mm") == 10.33 and _value(rows, "w_n", "rad/s") == 30.82
    assert "E A / L" in " ".join(rows["k"]) and "drum held" in " ".join(rows["w_n"])


def test_a_rope_of_given_stiffness(tmp_path):
    text = ROPE_FILE.read_text().replace("mass: 500 kg", "mass: 800 kg")
    wire = "  modulus: 100 GPa\n  metallic_area: 95 mm^2\n  free_length: 20 m\n"
    assert wire in text
    path = tmp_path / "given.yaml"
    path.write_text(text.replace(wire, "  stiffness: 300 kN/m\n"))
    rows = _rows(path)
    expected = _rope_numbers(300e3, 800.0)
    assert _value(rows, "m[load]", "kg") == 800.0
    for symbol, unit in (("k", "kN/m"), ("s_st", "mm"), ("w_n", "rad/s"), ("f_n", "Hz")):
        assert _value(rows, symbol, unit) == pytest.approx(expected[symbol], rel=5e-4), symbol
    assert "as given" in " ".join(rows["k"])


def test_a_drawn_load_on_its_rope(tmp_path):
    text = (SCENARIOS / "compliant_hoist.yaml").read_text()
    load = "mass: 500 kg}"
    assert text.count(load) == 1
    path = tmp_path / "drawn.yaml"
    path.write_text(text.replace(load, "mass: 500 kg,\n         rope: {modulus: 100 GPa, metallic_area: 50 mm^2, "
                                       "free_length: 10 m}}"))
    rows = _rows(path)
    expected = _rope_numbers(100e9 * 50e-6 / 10.0, 500.0)  # 500 kN/m
    assert _value(rows, "m[load]", "kg") == 500.0
    for symbol, unit in (("k", "kN/m"), ("s_st", "mm"), ("w_n", "rad/s"), ("f_n", "Hz")):
        assert _value(rows, symbol, unit) == pytest.approx(expected[symbol], rel=5e-4), symbol


def test_no_rope_no_rope_rows():
    rows = _rows(SCENARIOS / "exercise6_direct_start.yaml")
    assert not {"k", "s_st", "w_n", "f_n"} & set(rows) and not any(s.startswith("m[") for s in rows)
    assert rows["J[pinion]"][-1] == "kg*m^2"

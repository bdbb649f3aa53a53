"""Values a scenario accepts that may not say what was meant: a bare number on any key with a unit (read in SI:
``drum: diameter: 40`` is a 40 m drum) and a value far outside what its part measures are warned of, one line
each naming the key, its file and line and how the number was read; ``--strict`` makes each an error (exit 2,
one line, nothing written).  No test here simulates: a guard makes sure."""

from __future__ import annotations

import pytest
from click.testing import CliRunner
from helpers import BASE, SCENARIOS, line_of

from hoistsim.cli import main
from hoistsim.running import simulation

DRUM = "  diameter: 40 cm"
ROPE_FILE = SCENARIOS / "lift_off_the_ground.yaml"
DRAWN_FILE = SCENARIOS / "modelica" / "First.yaml"


@pytest.fixture(autouse=True)
def _no_simulation(monkeypatch):
    monkeypatch.setattr(simulation, "simulate", lambda *a, **k: pytest.fail("a warning's check must not simulate"))


def _cli(args: list[str]):
    result = CliRunner().invoke(main, args)
    return result, result.stderr.splitlines()


def _write(tmp_path, text: str, name: str = "scenario.yaml"):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def _warned(tmp_path, text: str, *options: str) -> list[str]:
    result, lines = _cli(["check", str(_write(tmp_path, text)), *options])
    assert result.exit_code == 0, result.output
    assert all(line.startswith("hoistsim: warning: ") for line in lines), lines
    return [line.removeprefix("hoistsim: warning: ") for line in lines]


def test_a_bare_length_is_metres_and_said_with_its_key_line_and_reading(tmp_path):
    """40 on the drum's diameter is a 40 m drum: far outside a drum's, said in the same line."""
    text = BASE.replace(DRUM, "  diameter: 40")
    path = tmp_path / "scenario.yaml"
    assert _warned(tmp_path, text) == [
        f"{path}:{line_of(text, '  diameter: 40')}: drum.diameter: the bare number 40 is read as 40 m, far outside "
        "a hoist drum's diameter (50 mm to 5 m); write the unit, like '20 cm', to say which you mean"]


def test_a_plausible_bare_number_is_still_said_and_a_value_with_its_unit_is_silent(tmp_path):
    text = BASE.replace(DRUM, "  diameter: 0.4").replace("  mass: 500 kg", "  mass: 500")
    said = _warned(tmp_path, text)
    assert [line.split(": ", 2)[1:] for line in said] == [
        ["drum.diameter", "the bare number 0.4 is read as 0.4 m; write the unit, like '20 cm', to say which you mean"],
        ["load.mass", "the bare number 500 is read as 500 kg; write the unit, like '500 kg', to say which you mean"]]
    assert _warned(tmp_path, BASE) == []


def test_zero_is_zero_in_any_unit_and_a_pure_number_has_none(tmp_path):
    text = BASE.replace("  mass: 500 kg", "  mass: 0")
    assert _warned(tmp_path, text) == []


def test_a_value_far_outside_its_part_with_its_unit_is_said(tmp_path):
    """A wire rope of 0.04 mm^2 (a 0.04 mm figure typed as its area): its unit was written, the value is not
    a rope's."""
    text = ROPE_FILE.read_text(encoding="utf-8").replace("metallic_area: 95 mm^2", "metallic_area: 0.04 mm^2")
    path = tmp_path / "scenario.yaml"
    assert _warned(tmp_path, text) == [
        f"{path}:{line_of(text, 'metallic_area')}: rope.metallic_area: 0.04 mm^2 is far outside a wire rope's "
        "metallic area (1 mm^2 to 5000 mm^2): check it and its unit"]


def test_a_bare_number_in_a_tables_row_names_the_row(tmp_path):
    text = BASE.replace("engagement_force: 3201 N", "engagement_force: [[0 s, 0 N], [0.5 s, 3201]]")
    said = _warned(tmp_path, text)
    assert len(said) == 1 and said[0].endswith(
        "clutch.engagement_force: row 2: the bare number 3201 is read as 3201 N; write the unit, like '200 daN', to "
        "say which you mean"), said


def test_a_drawn_parts_bare_number_names_the_part(tmp_path):
    text = DRAWN_FILE.read_text(encoding="utf-8").replace("inertia2: {inertia: 2 kg*m^2", "inertia2: {inertia: 2")
    said = _warned(tmp_path, text)
    assert len(said) == 1 and ": drivetrain.shafts.inertia2.inertia: the bare number 2 is read as 2 kg*m^2; " in said[0]


def test_set_and_sweep_values_are_said_under_their_option(tmp_path):
    assert _warned(tmp_path, BASE, "--set", "drum.diameter=0.04") == [
        "--set: drum.diameter: the bare number 0.04 is read as 0.04 m, far outside a hoist drum's diameter (50 mm "
        "to 5 m); write the unit, like '20 cm', to say which you mean"]
    text = BASE + "sweep:\n  drum.diameter: [30 cm, 0.4, 40 m]\n"
    path = tmp_path / "scenario.yaml"
    at = line_of(text, "drum.diameter: [")
    assert _warned(tmp_path, text) == [
        f"{path}:{at}: sweep.drum.diameter: item 2: the bare number 0.4 is read as 0.4 m; write the unit, like "
        "'20 cm', to say which you mean",
        f"{path}:{at}: sweep.drum.diameter: item 3: 40 m is far outside a hoist drum's diameter (50 mm to 5 m): "
        "check it and its unit"]
    # a range's values between its ends are the range's own numbers: only the ends are the user's
    ranged = BASE + "sweep:\n  drum.diameter: {from: 30 cm, to: 50 cm, count: 5}\n"
    assert _warned(tmp_path, ranged) == []


@pytest.mark.parametrize("command", [["check"], ["run", "-o", "{out}"], ["statics"]])
def test_strict_makes_a_warning_an_error_and_writes_nothing(tmp_path, command):
    text = BASE.replace(DRUM, "  diameter: 40")
    path = _write(tmp_path, text)
    out = tmp_path / "out.h5"
    result, lines = _cli([command[0], str(path), *[a.format(out=out) for a in command[1:]], "--strict"])
    assert result.exit_code == 2, result.output
    assert lines == [f"hoistsim: error: {path}:{line_of(text, '  diameter: 40')}: drum.diameter: the bare number 40 "
                     "is read as 40 m, far outside a hoist drum's diameter (50 mm to 5 m); write the unit, like "
                     "'20 cm', to say which you mean (an error under --strict)"]
    assert "Traceback" not in result.output and not out.exists()
    result, lines = _cli([command[0], str(_write(tmp_path, BASE)), "--strict"] if command == ["check"] else
                         ["check", str(_write(tmp_path, BASE)), "--strict"])
    assert result.exit_code == 0 and lines == []


def test_a_bare_numbers_example_is_in_the_keys_own_unit(tmp_path):
    """A gear's module is written in mm: its bare number's example is a module ('4 mm', the middle of a module's
    plausible range), not a length of another part that would itself be warned of ('20 cm')."""
    said = _warned(tmp_path, BASE.replace("module: 4 mm", "module: 4"))
    assert len(said) == 1 and said[0].endswith(
        "gears.module: the bare number 4 is read as 4 m, far outside a gear's module (0.3 mm to 50 mm); write the "
        "unit, like '4 mm', to say which you mean"), said


def test_strict_says_every_bare_number_then_fails_once(tmp_path):
    """Four bare numbers under --strict: each said, as an error with its file, line and key, then exit 2 once
    (it stopped at the first: a user fixed one and ran again, three times), nothing written."""
    text = (BASE.replace("  mass: 500 kg", "  mass: 500").replace("module: 4 mm", "module: 0.004")
            .replace(DRUM, "  diameter: 0.4").replace("stall_torque: 500 N*m", "stall_torque: 500"))
    path = _write(tmp_path, text)
    out = tmp_path / "out.h5"
    result, lines = _cli(["run", str(path), "-o", str(out), "--strict"])
    assert result.exit_code == 2, result.output
    assert "Traceback" not in result.output and result.stdout == "" and not out.exists()
    assert [line.split(": ")[:3] for line in lines] == [
        ["hoistsim", "error", f"{path}:{line_of(text, fragment)}"] for fragment in
        ("stall_torque: 500", "module: 0.004", "diameter: 0.4", "  mass: 500")], lines
    assert [line.split(": ")[3] for line in lines] == ["motor.stall_torque", "gears.module", "drum.diameter",
                                                       "load.mass"], lines
    assert all(line.endswith("(an error under --strict)") for line in lines), lines


def test_watch_under_strict_says_every_bare_number(tmp_path):
    """`watch --strict` says each value as `run --strict` does, one line each, the last saying the results stay."""
    from hoistsim.cli.watching import Watch

    text = BASE.replace("  mass: 500 kg", "  mass: 500").replace(DRUM, "  diameter: 0.4")
    said: list[str] = []
    watched = Watch(_write(tmp_path, text), output=tmp_path / "out.h5", strict=True, echo=said.append)
    assert not watched.run()
    assert [line.split(": ")[3] for line in said] == ["drum.diameter", "load.mass"], said
    assert all(line.startswith("hoistsim: error: ") for line in said), said
    assert not (tmp_path / "out.h5").exists()

"""What a machine's outputs are called: each name made by one element, and a series or a summary, never both.

A results file holds every series (on run and time) and every summary (on run) side by side in one group, each
under its name: a bearing friction that named its heat ``<name>_energy`` both ways could not be written (its
rows where the summary's one value goes).  The names are checked where the layout makes them, for every element.
"""

from __future__ import annotations

import h5py
import pytest
from click.testing import CliRunner
from helpers import SCENARIOS

from hoistsim import load_scenario, scenario_from_dict
from hoistsim._pytree import static
from hoistsim.cli import main
from hoistsim.errors import ScenarioError
from hoistsim.machine.assemble import machine_elements
from hoistsim.machine.core.element import AbstractElement
from hoistsim.machine.core.layout import Layout, LayoutError


class NamesOnly(AbstractElement):
    """An element that brings nothing but the names of its outputs."""

    section: str = static("")
    series: tuple = static(())
    summary_names: tuple = static(())

    @classmethod
    def from_spec(cls, spec) -> "NamesOnly":
        raise NotImplementedError("built in the tests alone")

    @property
    def columns(self) -> dict:
        return {name: ("1", f"{name} of {self.section}") for name in self.series}

    @property
    def summaries(self) -> dict:
        return {name: "1" for name in self.summary_names}


def _one_shaft_with_a_bearing_friction():
    return scenario_from_dict({
        "name": "bearing", "simulation": {"duration": "1 s", "output_interval": "10 ms"},
        "drivetrain": {"shafts": {"rotor": {"inertia": "1 kg*m^2", "speed": "2 rad/s"}},
                       "bearing_frictions": {"bearing": {"shaft": "rotor", "torque": "1 N*m"}}}})


@pytest.mark.parametrize("scenario", [_one_shaft_with_a_bearing_friction, lambda: load_scenario(
    SCENARIOS / "modelica" / "LossyGearDemo2.yaml")], ids=["one-shaft", "LossyGearDemo2"])
def test_a_bearing_friction_names_its_heat_a_series_and_a_summary_apart(scenario):
    """Its heat so far is the series ``<name>_energy`` and at the end the summary ``<name>_slip_energy`` (a
    clutch's names); no element of the scene names an output both ways."""
    elements = machine_elements(scenario())
    for element in elements:
        assert not set(element.columns) & set(element.summaries), element.section
    layout = Layout(elements)
    name = next(e.section for e in elements if type(e).__name__ == "BearingFriction")
    assert layout.columns()[f"{name}_energy"][0] == "J"
    assert layout.summaries[f"{name}_slip_energy"] == "J"
    assert f"{name}_energy" not in layout.summaries and f"{name}_slip_energy" not in layout.columns()


def test_a_one_shaft_scene_with_a_bearing_friction_is_written_whole(tmp_path):
    """``hoistsim run`` to a file: its heat a series on (run, time) and a summary on (run), the last row the
    summary (once an internal error, the rows where the summary's one value goes, and nothing written)."""
    scene = tmp_path / "bearing.yaml"
    scene.write_text("name: bearing\nsimulation: {duration: 3 s, output_interval: 10 ms}\n"
                     "drivetrain:\n  shafts: {rotor: {inertia: 1 kg*m^2, speed: 2 rad/s}}\n"
                     "  bearing_frictions: {bearing: {shaft: rotor, torque: 1 N*m}}\n", encoding="utf-8")
    out = tmp_path / "bearing.h5"
    result = CliRunner().invoke(main, ["run", str(scene), "-o", str(out)])
    assert result.exit_code == 0, (result.output, result.exception)
    with h5py.File(out, "r") as f:
        series, summary = f["runs/bearing_energy"], f["runs/bearing_slip_energy"]
        assert series.shape == (1, 301) and summary.shape == (1,)
        # the rotor stops in 2 s under 1 N*m: its whole kinetic energy, 2 J, turned into heat
        assert series[0, -1] == summary[0] == pytest.approx(2.0, rel=1e-9)


def test_the_figures_title_tells_a_bearing_frictions_story_by_its_summarys_names():
    """The run figure's title finds a bearing friction by the names its summary has (its slip duration and
    heat), and says its heat."""
    from hoistsim.display.friction_clutch import FRICTION_CLUTCH

    layout = Layout(machine_elements(_one_shaft_with_a_bearing_friction()))
    summary = {name: 0.25 for name in layout.summaries} | {"bearing_slip_energy": 3.0}
    assert FRICTION_CLUTCH.headline(summary) == "bearing never locks (3 J of heat up to the end)"


def test_an_output_named_both_a_series_and_a_summary_is_refused():
    element = NamesOnly(section="part", series=("part_heat",), summary_names=("part_heat",))
    with pytest.raises(LayoutError, match="'part_heat' is both a series and a summary of 'part'") as raised:
        Layout((element,))
    assert raised.value.key == "part"


@pytest.mark.parametrize("first, second, said", [
    (("a_torque",), (), "a series of 'a' and a series of 'b'"),
    ((), ("a_torque",), "a series of 'a' and a summary of 'b'"),
])
def test_an_output_two_elements_name_is_refused(first, second, said):
    a = NamesOnly(section="a", series=("a_torque",))
    b = NamesOnly(section="b", series=first, summary_names=second)
    with pytest.raises(LayoutError, match=f"'a_torque' is {said}") as raised:
        Layout((a, b))
    assert raised.value.key == "b"


def test_an_output_two_summaries_name_is_refused():
    a, b = (NamesOnly(section=name, summary_names=("peak",)) for name in "ab")
    with pytest.raises(LayoutError, match="'peak' is a summary of 'a' and a summary of 'b'"):
        Layout((a, b))


def test_parts_whose_names_make_the_same_output_are_a_scenario_error():
    """A clutch ``c`` and a bearing friction ``c_slip``: the clutch's summary ``c_slip_energy`` is the bearing
    friction's series; said as the scene is checked, before anything compiles."""
    scenario = scenario_from_dict({
        "name": "clash", "simulation": {"duration": "1 s", "output_interval": "10 ms"},
        "drivetrain": {"shafts": {"a": {"inertia": "1 kg*m^2", "speed": "1 rad/s"}, "b": {"inertia": "1 kg*m^2"}},
                       "clutches": {"c": {"between": ["a", "b"], "static_friction": 0.3, "kinetic_friction": 0.2,
                                          "effective_radius": "0.1 m", "force": "100 N"}},
                       "bearing_frictions": {"c_slip": {"shaft": "a", "torque": "1 N*m"}}}})
    with pytest.raises(ScenarioError, match="c_slip: output 'c_slip_energy' is a summary of 'c' and a series of "
                                            "'c_slip'"):
        machine_elements(scenario)


def test_the_names_of_every_shipped_scene_are_made_once():
    """Every shipped scenario and Modelica example: each output one element's, a series or a summary."""
    for path in sorted(SCENARIOS.glob("*.yaml")) + sorted((SCENARIOS / "modelica").glob("*.yaml")):
        elements = machine_elements(load_scenario(path))
        made = [name for e in elements for name in (*e.columns, *e.summaries)]
        assert len(made) == len(set(made)), (path.name, sorted({n for n in made if made.count(n) > 1}))

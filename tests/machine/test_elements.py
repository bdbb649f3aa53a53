"""New elements against independent answers, and the core's promises about elements.

Each element is checked against something that does not use it: a flywheel
against the same inertia given to the shaft directly, a rim against its
formula, a torque-speed table against the linear motor it lies on, a motor
that is off against the closed form of two inertias meeting through a
slipping clutch.
"""

from __future__ import annotations

import ast
import copy
import dataclasses
import inspect
import math
import re

import jax
import numpy as np
import pytest
from helpers import EXERCISE6, ROOT

from hoistsim import scenario_from_dict, simulate
from hoistsim.machine.assemble import build_plan, log_rows, step_room
from hoistsim.machine.core.element import AbstractCoupling, AbstractElement, abstract_methods
from hoistsim.machine.core.loop import OK, compiled_run
from hoistsim.machine.elements import REGISTRY, Shaft, element_class, element_sections, elements_for
from hoistsim.running.block_plans import _same_element
from hoistsim.scenario.lowering import lower, lowered_again

TIGHT = {"rtol": 1e-10, "atol": 1e-12}
# A start that slips, locks, and lifts: every mode of the clutch and a moving drum.
RAMP = [["0 s", "0 N"], ["0.2 s", "0 N"], ["0.6 s", "6000 N"]]


def _scene(**sections):
    data = copy.deepcopy(EXERCISE6)
    data["clutch"]["engagement_force"] = RAMP
    data["simulation"].update(duration="1.5 s", **TIGHT)
    for key, value in sections.items():
        if value is None:
            data.pop(key, None)
        elif isinstance(value, dict) and isinstance(data.get(key), dict):
            data[key].update(value)
            data[key] = {k: v for k, v in data[key].items() if v is not None}
        else:
            data[key] = value
    return scenario_from_dict(data)


def _speeds(run):
    return run["motor_speed"], run["drum_speed"]


@pytest.mark.parametrize("shaft, section, key, base", [("motor", "motor", "inertia", 0.9),
                                                        ("drum", "drum", "inertia", 40.0)])
@pytest.mark.slow
def test_flywheel_equals_its_inertia_on_the_shaft(shaft, section, key, base):
    extra = 7.5
    with_flywheel = simulate(_scene(flywheel={"shaft": shaft, "inertia": f"{extra} kg*m^2"}))
    heavier = simulate(_scene(**{section: {key: f"{base + extra} kg*m^2"}}))
    assert with_flywheel.events["kind"].tolist() == heavier.events["kind"].tolist()
    np.testing.assert_allclose(with_flywheel.events["time"], heavier.events["time"], atol=1e-10)
    for ours, theirs in zip(_speeds(with_flywheel), _speeds(heavier)):
        assert np.max(np.abs(ours - theirs)) < 1e-8
    assert with_flywheel.energy_balance["relative_residual"] < 1e-8


@pytest.mark.slow
def test_rim_inertia_is_the_formula():
    rim = {"density": "7200 kg/m^3", "outer_diameter": "80 cm", "inner_diameter": "60 cm", "width": "12 cm"}
    s = _scene(flywheel=rim)
    expected = math.pi * 7200 * 0.12 * (0.4**4 - 0.3**4) / 2
    assert s.flywheel.moment_of_inertia == pytest.approx(expected, rel=1e-14)
    (flywheel,) = [e for e in elements_for(s) if e.section == "flywheel"]
    assert flywheel.inertias() == (("motor", pytest.approx(expected, rel=1e-14)),)
    # and the run sees it: the same as that inertia given directly
    direct = simulate(_scene(flywheel={"inertia": f"{expected!r} kg*m^2"}))
    np.testing.assert_allclose(simulate(s)["motor_speed"], direct["motor_speed"], rtol=0, atol=1e-12)


@pytest.mark.slow
def test_torque_speed_table_on_the_line_is_the_linear_motor():
    c0, w0 = 500.0, 300 * math.pi / 30
    rows = [[f"{float(w)!r} rad/s", f"{float(c0 * (1 - w / w0))!r} N*m"] for w in np.linspace(0.0, w0, 7)]
    table = _scene(motor={"stall_torque": None, "no_load_speed": None, "torque_speed": rows})
    data = table.raw
    assert "stall_torque" not in data["motor"]
    linear = simulate(_scene())
    tabled = simulate(table)
    assert tabled.events["kind"].tolist() == linear.events["kind"].tolist()
    for ours, theirs in zip(_speeds(tabled), _speeds(linear)):
        assert np.max(np.abs(ours - theirs)) < 1e-8
    assert tabled.summary["slip_energy"] == pytest.approx(linear.summary["slip_energy"], rel=1e-8)


def test_table_is_continued_linearly_beyond_its_ends():
    from hoistsim.machine.elements import TableMotor

    motor = TableMotor(inertia=1.0, table_speeds=np.array([10.0, 20.0, 30.0]),
                       table_torques=np.array([100.0, 80.0, 20.0]))
    speeds = np.array([-10.0, 0.0, 15.0, 25.0, 40.0])
    np.testing.assert_allclose(np.asarray(motor.characteristic(speeds)), [140.0, 120.0, 90.0, 50.0, -40.0])


@pytest.mark.slow
def test_motor_off_meets_a_second_inertia_through_a_slipping_clutch():
    """Closed form: J_a w' = -T, J_b w' = T until the speeds meet."""
    w1, force = 30.0, 2000.0
    run = simulate(_scene(motor={"stall_torque": None, "no_load_speed": None, "torque": "0 N*m"},
                          clutch={"engagement_force": f"{force} N"}, load={"mass": "0 kg"},
                          initial={"motor_speed": f"{w1} rad/s"}))
    tau = 90 / 17
    ja, jb = 0.9, 40.0 / tau**2  # the motor's inertia; the drum's, at the pinion
    from hoistsim.components import ConeClutch

    torque = 0.1 * ConeClutch(0.20, 0.24, math.radians(25), 0.3, 0.1).torque_per_newton * force
    lock = ja * jb * w1 / (torque * (ja + jb))
    heat = ja * jb * w1**2 / (2 * (ja + jb))
    assert run.events["kind"].tolist() == ["lock"]
    assert abs(run.lockup_time - lock) < 1e-8 * lock
    assert abs(run.slip_energy - heat) < 1e-8 * heat
    assert run["motor_torque"].max() == 0.0 and run.energy_balance["motor_work"] == 0.0
    # after the lock both turn at the common speed, momentum kept
    assert run["motor_speed"][-1] == pytest.approx(ja * w1 / (ja + jb), rel=1e-10)


def test_a_scene_names_only_its_elements():
    plain = build_plan(_scene())[0].layout
    # the sections its elements are built from, in the registry's order as any drivetrain's (the hoist's
    # template draws some as several parts: the motor shaft and the motor, the pinion and drum shafts)
    assert [section for section, _, _ in element_sections(_scene())] == [
        "motor", "gears", "gears", "drum", "motor", "clutch", "load"]
    assert plain.bodies == ["motor", "pinion"]
    # the load is a mass on a line: its height is its position, the angle the core keeps of a body it is
    assert plain.state_names == ["motor.speed", "pinion.speed", "motor_work", "clutch_energy", "load_angle"]
    heavy = build_plan(_scene(flywheel={"inertia": "3 kg*m^2"}))[0].layout
    assert heavy.state_names == plain.state_names and heavy.columns() == plain.columns()


class _SecondBrake(AbstractCoupling):
    """A brake on the pinion shaft: with a brake on the drum, the same motion held twice."""

    section = "pinion_brake"
    can_slip = False

    @classmethod
    def from_spec(cls, spec):
        return cls()

    def joins(self):
        return ("pinion", None)

    def is_open(self, segment):
        return segment.middle >= 0.25

    def capacity(self, x):
        return math.inf

    def sliding_torque(self, x):
        return 0.0


@pytest.mark.slow
def test_two_couplings_holding_the_same_motion_share_it_by_order():
    # The drum brake holds the output shaft, and a second brake holds it again until 0.25 s: the torque
    # is statically indeterminate; the first in the machine's order takes it all, and the run is the
    # same as with the drum brake alone.
    plan, _ = build_plan(_scene(brake={"release_time": "0.5 s"}))
    both = dataclasses.replace(plan, elements=plan.elements + (_SecondBrake(),))
    alone, twice = (jax.device_get(compiled_run("tsit5", log_rows(plan), step_room(plan))(p)) for p in (plan, both))
    assert int(twice.counters[2]) == OK
    assert np.array_equal(twice.grid_state, alone.grid_state)


def test_the_core_names_no_part_of_the_machine():
    core = ROOT / "hoistsim" / "machine" / "core"
    for path in core.glob("*.py"):
        text = path.read_text(encoding="utf-8")
        found = re.findall(r"\b(clutch|brake|load|motor|drum|pinion|gear)\w*", text, flags=re.IGNORECASE)
        assert not found, f"{path.name} names {sorted(set(found))}"


def test_a_new_part_is_its_keys_one_element_file_one_registry_line_and_its_display():
    """The eddy-current brake, the worked example of docs/architecture.md: its keys (its spec, its field on the
    drivetrain), its element's file, its registry line, its display and its place among the displays are every
    module that names it (and the heat capacitor's, a part that holds one to warm from it).  The references are
    left out: they name Modelica's examples, one of which is called EddyCurrentBrake too."""
    package = ROOT / "hoistsim"
    naming = {path.relative_to(package).as_posix() for path in package.rglob("*.py")
              if path.parent.name != "references" and re.search(r"\b(EddyCurrentBrake\w*|eddy_current_brakes?)\b", path.read_text(encoding="utf-8"))}
    assert naming == {"scenario/schema_speed_torques.py", "scenario/schema_drivetrain.py",
                      "machine/elements/eddy_current_brake.py", "machine/elements/__init__.py",
                      "machine/elements/heat_capacitor.py", "display/eddy_current_brake.py", "display/__init__.py"}


def test_no_module_beyond_the_elements_builds_or_reads_an_element_by_its_class():
    """The lowering, the assembly, the core, the loop, the sweeps, the results and the figures serve every part
    without naming one: a new part needs no change there.  (The tables ``check`` prints of a scene's motors and
    ropes are a study of those parts.)"""
    classes = {cls.__name__ for cls in registered_classes()}
    package = ROOT / "hoistsim"
    for path in package.rglob("*.py"):
        where = path.relative_to(package).as_posix()
        if where.startswith("machine/elements/") or where == "studies/machine_tables.py":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        used = {node.id for node in ast.walk(tree) if isinstance(node, ast.Name)}
        used |= {node.attr for node in ast.walk(tree) if isinstance(node, ast.Attribute)}
        used |= {alias.name for node in ast.walk(tree) if isinstance(node, (ast.Import, ast.ImportFrom))
                 for alias in node.names}
        assert not used & classes, f"{where} names {sorted(used & classes)}"


def test_every_element_is_one_file_named_after_it():
    folder = ROOT / "hoistsim" / "machine" / "elements"
    classes = registered_classes()
    for cls in classes:
        module = cls.__module__.rsplit(".", 1)[-1]
        assert (folder / f"{module}.py").exists()
        assert sum(1 for c in classes if c.__module__ == cls.__module__) == 1, module


def test_an_element_without_from_spec_fails_where_it_is_defined():
    with pytest.raises(TypeError, match=r"^_Unbuilt lacks from_spec: an element \(a class whose name does not start "
                                        r"with Abstract\) must define every abstract method"):
        class _Unbuilt(AbstractElement):
            section = "unbuilt"

            def inertias(self):
                return (("pinion", 1.0),)


def test_a_coupling_without_its_numbers_fails_where_it_is_defined():
    with pytest.raises(TypeError, match=r"^_Unbounded lacks capacity: "):
        class _Unbounded(AbstractCoupling):
            section = "unbounded"

            @classmethod
            def from_spec(cls, spec):
                return cls()

            def joins(self):
                return ("pinion", None)

            def sliding_torque(self, x):
                return 0.0

    with pytest.raises(TypeError, match=r"^_Bare lacks capacity, from_spec, joins, sliding_torque: "):
        class _Bare(AbstractCoupling):
            section = "bare"


def test_an_abstract_class_leaves_its_methods_to_the_classes_below_it():
    class AbstractPinionHold(AbstractCoupling):  # named Abstract...: may leave methods abstract
        def joins(self):
            return ("pinion", None)

    assert abstract_methods(AbstractPinionHold) == ["capacity", "from_spec", "sliding_torque"]

    class _PinionHold(AbstractPinionHold):
        capacity_torque: object  # N*m
        section = "pinion_hold"

        @classmethod
        def from_spec(cls, spec):
            return cls(capacity_torque=spec)

        def capacity(self, x):
            return self.capacity_torque

        def sliding_torque(self, x):
            return 0.0

    hold = _PinionHold.from_spec(250.0)
    assert abstract_methods(_PinionHold) == [] and hold.joins() == ("pinion", None)
    # still a frozen pytree dataclass: its field a traced leaf
    assert jax.tree_util.tree_leaves(hold) == [250.0]
    with pytest.raises(dataclasses.FrozenInstanceError):
        hold.capacity_torque = 1.0


def test_every_registered_element_is_built_from_its_part_alone():
    for cls in registered_classes():
        assert list(inspect.signature(cls.from_spec).parameters) == ["spec"], cls.__name__


def registered_classes() -> list:
    """The element class of every registry entry (a part with variants: each variant's)."""
    return list(dict.fromkeys(c for entry in REGISTRY.values()
                              for c in (entry.values() if isinstance(entry, dict) else [entry])))


def test_a_hoist_is_lowered_to_drawn_parts_each_built_from_its_spec_alone():
    """Every hoist section the template draws is lowered to drawn parts under the registry's paths; a part's
    element is built from its spec alone, the same again when the part is written out again from the scenario;
    and another value of what a part reads of the scenario (the start) is another part."""
    lossy = {"efficiency": 0.95}
    heating = {"heat_capacity": "2.4 kJ/K", "cooling": "20 W/K", "ambient_temperature": "25 degC",
               "static_friction": [["25 degC", 0.3], ["300 degC", 0.22]]}
    ripple = {"period": "360 deg", "harmonics": [{"order": 1, "amplitude": "5 N*m"}]}
    scenes = [_scene(), _scene(gears=lossy, clutch_heating=heating, initial={"motor_speed": "100 rpm"}),
              # every other hoist section the template draws
              _scene(motor={"ripple": ripple}, drum={"resisting_ripple": ripple}, flywheel={"inertia": "1 kg*m^2"},
                     reciprocating={"mass": "2 kg", "crank_radius": "0.1 m", "rod_length": "0.4 m"},
                     brake={"release_time": "0.1 s", "static_torque": "900 N*m"}, ratchet={},
                     rope={"stiffness": "2 MN/m"}, ground={"hoisting_class": "HC2"},
                     bearings={"gear_offset": "0.1 m", "rope_offset": "0.3 m", "span": "0.8 m"})]
    drawn = 0
    for scenario in scenes:
        lowered = lower(scenario, REGISTRY)
        for part in lowered.parts:
            assert part.path in REGISTRY and part.template is not None, part.section
            element = element_class(part).from_spec(part.spec)
            again = lowered_again(part, lowered.scenario)
            assert _same_element(element, element_class(again).from_spec(again.spec)), part.section
            drawn += 1
    assert drawn >= 25
    base = scenes[0]
    (shaft,) = [e for e in elements_for(base) if e.section == "motor" and isinstance(e, Shaft)]
    faster = base.model_copy(update={"initial": base.initial.model_copy(update={"motor_speed": 9.0})})
    (again,) = [e for e in elements_for(faster) if e.section == "motor" and isinstance(e, Shaft)]
    assert shaft.initial_speed == base.initial.motor_speed and again.initial_speed == 9.0

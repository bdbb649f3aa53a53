"""What the run figure draws of a drawn drivetrain's parts: each kind its panels, named as the user named the
parts, and no panel of the hoist's part whose name a drawn part happens to share."""

from __future__ import annotations

import numpy as np

from hoistsim.figures.runs import _panels
from hoistsim.results.part_names import with_part_names

_T = np.linspace(0.0, 1.0, 5)


def _run(drivetrain: dict) -> dict:
    """A run read back: its parameters, and a column of zeros for every name its panels might read."""
    run = {"parameters": {"drivetrain": drivetrain}, "time": _T}
    names = ["torque1"]
    for kind in ("clutches", "one_way_clutches", "bearing_frictions"):
        for name in drivetrain.get(kind, {}):
            names += [f"{name}_torque", f"{name}_slip", f"{name}_capacity", f"{name}_engaged", f"{name}_mode"]
    for name in drivetrain.get("eddy_current_brakes", {}):
        names.append(f"{name}_loss_power")
    for name in drivetrain.get("heat_capacitors", {}):
        names.append(f"{name}_temperature")
    for name in drivetrain.get("planetaries", {}):
        names += [f"{name}_{word}_torque" for word in ("sun", "carrier", "ring")]
    run.update({name: np.zeros_like(_T) for name in names + [f"{s}_speed" for s in drivetrain["shafts"]]})
    return with_part_names(run, run["parameters"])


def test_a_clutch_named_brake_is_drawn_as_a_clutch_not_as_the_hoists_brake():
    """Modelica's Friction names a clutch to the ground `brake` and a clutch `clutch`: their torques and slips, not
    the hoist's brake (its torque at the drum, holding the load up) nor its cone clutch."""
    run = _run({"shafts": {"a": {}, "b": {}}, "torques": [{"shaft": "a"}],
                "clutches": {"clutch": {"between": ["a", "b"]}, "brake": {"between": ["b", "ground"]}}})
    names = [panel.name for panel in _panels(set(run), run)]
    assert names == ["shaft_speeds", "shaft_torques", "clutch_slips", "clutch_torque", "brake_torque"], names


def test_every_new_kind_of_part_has_its_panel():
    run = _run({"shafts": {"a": {}, "b": {}, "c": {}}, "torques": [{"shaft": "a"}],
                "one_way_clutches": {"freewheel": {"between": ["a", "b"]}},
                "bearing_frictions": {"bearing": {"shaft": "c", "torque": 2.0, "peak": 1.5}},
                "eddy_current_brakes": {"eddy": {"shaft": "c"}}, "heat_capacitors": {"pads": {}},
                "planetaries": {"set": {"sun": "a", "carrier": "b", "ring": "c"}}})
    panels = {panel.name: [trace.label for trace in panel.traces] for panel in _panels(set(run), run)}
    assert panels["clutch_slips"] == ["freewheel", "bearing"]
    assert "freewheel_torque" in panels and "bearing_torque" in panels
    assert panels["eddy_current_power"] == ["eddy"] and panels["capacitor_temperature"] == ["pads"]
    assert panels["set_torques"] == ["sun", "carrier", "ring"]
    assert panels["shaft_torques"] == ["torque1 on a"]

"""The drivetrain a hoist scenario stands for, written out as a scenario of its own (``hoistsim check
--drivetrain``): the parts the scenario is lowered to (:mod:`hoistsim.scenario.lowering`) with their keys, in SI
units, and the names its outputs take there.

Run, it gives the hoist's motion under the drawn parts' names (``clutch_slip`` for ``slip_speed``), to round-off:
the template's gear ratio z1/z2 is the drawn stage's 1 / (z2/z1).  The periodic regime's analysis (a hoist's
rows of each period) has no drawn key, and is left out.
"""

from __future__ import annotations

import io

from pydantic import BaseModel
from ruamel.yaml import YAML

from ..errors import ScenarioError
from ..scenario import units as u
from ..scenario.lowering import lower, output_names
from ..scenario.signals import TimeSignal
from ..scenario.tables import ForceTable

# the columns of each table key a drawn part may have
_TABLE_COLUMNS = {"torque_speed": (u.ANGULAR_SPEED, u.TORQUE), "static_friction": (u.TEMPERATURE, u.DIMENSIONLESS),
                  "kinetic_friction": (u.TEMPERATURE, u.DIMENSIONLESS), "table": (u.ANGLE, u.TORQUE)}
_STAGE = "mesh"  # the drawn gear stage's name, the template's (its lossy mesh's outputs: mesh_mesh_torque, ...)


def hoist_as_drivetrain(scenario) -> tuple[dict, dict[str, str]]:
    """(the hoist scenario as a drawn drivetrain's, plain data for YAML; each hoist output's name -> its drawn
    name where they differ)."""
    if scenario.drivetrain is not None:
        raise ScenarioError("drivetrain", "is drawn already: --drivetrain writes a hoist's sections out as one",
                            source=scenario.source)
    lowered = lower(scenario, ())  # a hoist's parts are its template's, in its order
    scenario = lowered.scenario  # started at its steady lift where it asks
    drawn: dict = {kind: {} for kind in ("shafts", "motors", "clutches", "gears", "rotors", "slider_cranks",
                                         "brakes", "ratchets")}
    renamed = {hoist: name for name, hoist in output_names(scenario).items() if hoist is not None}
    inertias: dict[str, float] = {}  # each shaft's, with the clutch's halves on it (a drawn clutch's are its shafts')
    for part in lowered.parts:
        if part.path.startswith("drivetrain."):
            _place(drawn, part.path.split(".")[1:], part.spec, scenario, inertias)
    for shaft, inertia in inertias.items():
        drawn["shafts"][shaft]["inertia"] = _value(inertia, u.INERTIA)
    out = {"name": f"{scenario.name}-drawn",
           "description": f"The drivetrain the hoist scenario {scenario.name} stands for.",
           "gravity": _value(scenario.gravity, u.ACCELERATION),
           "drivetrain": {kind: parts for kind, parts in drawn.items() if parts},
           "simulation": _plain(scenario.simulation)}
    return out, renamed


def hoist_as_drivetrain_text(scenario) -> str:
    """:func:`hoist_as_drivetrain` as a scenario file's text, its outputs' new names in a comment above it."""
    data, renamed = hoist_as_drivetrain(scenario)
    lines = [f"# {data['description']}", "# Its outputs are named after its parts; where the hoist's are not:"]
    lines += [f"#   {hoist} -> {drawn}" for hoist, drawn in renamed.items()]
    if scenario.periodic_regime is not None:
        lines.append("# The periodic regime's analysis (periodic:) is the hoist's only: it has no drawn key.")
    yaml = YAML()
    yaml.default_flow_style = None  # short lists ([motor, pinion], a table's rows) on one line
    yaml.width = 120
    text = io.StringIO()
    yaml.dump(data, text)
    return "\n".join(lines) + "\n" + text.getvalue()


def _place(drawn: dict, path: list, spec, scenario, inertias: dict) -> None:
    """Write one drawn part (or a key within one) into the drivetrain's plain data (``inertias``: each shaft's,
    written when every part is placed)."""
    kind, key = path[0], path[-1]
    if kind == "shafts" and key == "resisting_ripple":
        drawn["shafts"][spec.name]["resisting_ripple"] = _plain(spec.resisting_ripple)
    elif kind == "shafts":
        inertias[spec.name] = inertias.get(spec.name, 0.0) + spec.inertia
        shaft = {"inertia": None}  # its place, first
        root = spec.resolved("train")[0]
        if root != spec.name:  # turns with its root through the hoist's gears: a stage of its own
            gears = scenario.gears
            stage = {"between": [root, spec.name], "teeth": [gears.pinion_teeth, gears.wheel_teeth]}
            drawn["gears"][_STAGE] = {**stage, **drawn["gears"].get(_STAGE, {})}
        else:
            shaft["speed"] = _value(spec.speed, u.ANGULAR_SPEED)
        drawn["shafts"][spec.name] = shaft
    elif kind == "gears":  # a lossy mesh: its efficiencies on the stage
        drawn["gears"].setdefault(_STAGE, {}).update(
            {k: v for k, v in (("efficiency", spec.efficiency), ("backdrive_efficiency", spec.backdrive_efficiency))
             if v is not None})
    elif kind == "clutches" and key == "heating":
        drawn["clutches"].setdefault(spec.name, {})["heating"] = _plain(spec.heating)
    elif kind == "clutches":
        clutch = _plain(spec)
        clutch.pop("heating", None)
        clutch.pop("effective_radius", None)
        drawn["clutches"][spec.name] = {**clutch, **drawn["clutches"].get(spec.name, {})}
        for shaft, inertia in zip(spec.between, spec.resolved("halves")):
            inertias[shaft] = inertias.get(shaft, 0.0) + inertia
    elif kind == "load":
        drawn["load"] = _plain(spec)
    else:
        plain = _plain(spec)
        drawn[kind][spec.name] = plain


def _plain(model) -> dict:
    """A section's keys as a scenario writes them: numbers with their SI units, None left out."""
    out = {}
    derived = model.derived() if hasattr(model, "derived") else ()
    for name, field in type(model).model_fields.items():
        value = getattr(model, name, None)
        # (a template's own keys are excluded, as a part's name is; a key set from others is theirs to say)
        if value is None or field.exclude or name in derived:
            continue
        out[name] = _written(name, value, field)
    return out


def _written(name: str, value, field):
    if isinstance(value, TimeSignal):
        dimension = u.dimension_of(field)
        if value.has_harmonics:
            written = {"offset": _value(value.values[0], dimension),
                       "harmonics": [{"amplitude": _value(a, dimension), "frequency": f"{f!r} Hz",
                                      "phase": f"{p!r} rad"}
                                     for a, f, p in zip(value.amplitudes, value.frequencies, value.phases)]}
            if value.envelope_times is not None:
                written["envelope"] = [[f"{t!r} s", repr(v)] for t, v in zip(value.envelope_times,
                                                                              value.envelope_values)]
            return written
        return [[f"{t!r} s", _value(v, dimension)] for t, v in zip(value.times, value.values)]
    if isinstance(value, ForceTable):
        return [[f"{t!r} s", _value(v, u.FORCE)] for t, v in zip(value.times, value.forces)]
    if isinstance(value, BaseModel):
        return _plain(value)
    if name in _TABLE_COLUMNS and isinstance(value, tuple):  # a table (a clutch's static_friction is a number)
        first, second = _TABLE_COLUMNS[name]
        return [[_value(x, first), _value(y, second)] for x, y in value]
    if isinstance(value, (list, tuple)):
        return [_plain(v) if isinstance(v, BaseModel) else v for v in value]
    dimension = u.dimension_of(field)
    return _value(value, dimension) if dimension is not None else value


def _value(number: float, dimension) -> str | float:
    """A number in SI with its unit (exact: the float's own digits), bare where it has no unit."""
    if dimension is None or not dimension.si_unit:
        return float(number)
    return f"{float(number)!r} {dimension.si_unit}"

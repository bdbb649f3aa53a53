"""Scenario files: YAML -> a validated scenario in SI units.

Every problem with a scenario is raised as :class:`ScenarioError`, which names
the dotted key, the file and (where the YAML parser knows it) the line.  The
command line prints that one line and exits with status 2.
"""

from __future__ import annotations

import copy
import difflib
import io
import itertools
import json
import math
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import (
    BaseModel,
    BeforeValidator,
    ConfigDict,
    Field,
    PrivateAttr,
    ValidationError,
    model_validator,
)
from ruamel.yaml import YAML
from ruamel.yaml.comments import CommentedMap, CommentedSeq
from ruamel.yaml.error import MarkedYAMLError

from . import units as u

SOLVERS = ("tsit5", "dopri5", "dopri8", "bosh3", "heun", "kvaerno3", "kvaerno5")


class ScenarioError(ValueError):
    """A bad scenario: names the key, and the file and line where known."""

    def __init__(self, key: str, message: str, *, source: str | None = None, line: int | None = None):
        self.key = key
        self.message = message
        self.source = source
        self.line = line
        super().__init__(self.__str__())

    def __str__(self) -> str:
        where = ""
        if self.source:
            where = f"{self.source}:{self.line}: " if self.line else f"{self.source}: "
        key = f"{self.key}: " if self.key else ""
        return f"{where}{key}{self.message}"


def _quantity(dimension: u.Dimension):
    def convert(value: Any) -> float:
        try:
            return u.to_si(value, dimension)
        except u.UnitError as exc:
            raise ValueError(str(exc)) from None

    return BeforeValidator(convert)


Torque = Annotated[float, _quantity(u.TORQUE)]
AngularSpeed = Annotated[float, _quantity(u.ANGULAR_SPEED)]
Inertia = Annotated[float, _quantity(u.INERTIA)]
Mass = Annotated[float, _quantity(u.MASS)]
Length = Annotated[float, _quantity(u.LENGTH)]
Angle = Annotated[float, _quantity(u.ANGLE)]
Force = Annotated[float, _quantity(u.FORCE)]
Time = Annotated[float, _quantity(u.TIME)]
Acceleration = Annotated[float, _quantity(u.ACCELERATION)]
Number = Annotated[float, _quantity(u.DIMENSIONLESS)]


class ForceTable(BaseModel):
    """Engagement force against time, piecewise linear; a repeated time is a step.

    Before the first time the first force holds, after the last the last.
    """

    model_config = ConfigDict(frozen=True)
    times: tuple[float, ...]
    forces: tuple[float, ...]

    @property
    def is_constant(self) -> bool:
        return len(set(self.forces)) == 1


def _force_table(value: Any) -> ForceTable:
    if isinstance(value, ForceTable):
        return value
    if isinstance(value, (list, tuple)):
        if not value:
            raise ValueError("the force table is empty")
        times, forces = [], []
        for i, row in enumerate(value):
            if not isinstance(row, (list, tuple)) or len(row) != 2:
                raise ValueError(f"row {i} must be a pair [time, force], got {row!r}")
            try:
                t = u.to_si(row[0], u.TIME)
                f = u.to_si(row[1], u.FORCE)
            except u.UnitError as exc:
                raise ValueError(f"row {i}: {exc}") from None
            if not (math.isfinite(t) and math.isfinite(f)):
                raise ValueError(f"row {i} is not finite: {row!r}")
            if t < 0:
                raise ValueError(f"row {i}: time {t:g} s is before the start of the run")
            if f < 0:
                raise ValueError(f"row {i}: a clutch cannot be pushed apart (force {f:g} N < 0)")
            if times and t < times[-1]:
                raise ValueError(f"row {i}: time goes backwards ({t:g} s after {times[-1]:g} s)")
            if len(times) >= 2 and t == times[-1] == times[-2]:
                raise ValueError(f"row {i}: a time may appear at most twice (a step), {t:g} s appears three times")
            times.append(t)
            forces.append(f)
        return ForceTable(times=tuple(times), forces=tuple(forces))
    try:
        f = u.to_si(value, u.FORCE)
    except u.UnitError as exc:
        raise ValueError(f"{exc}, or a table [[time, force], ...]") from None
    if not math.isfinite(f):
        raise ValueError(f"force must be finite, got {value!r}")
    if f < 0:
        raise ValueError(f"a clutch cannot be pushed apart (force {f:g} N < 0)")
    return ForceTable(times=(0.0,), forces=(f,))


EngagementForce = Annotated[ForceTable, BeforeValidator(_force_table)]


class Section(BaseModel):
    model_config = ConfigDict(extra="forbid", frozen=True, allow_inf_nan=False)


class MotorSpec(Section):
    stall_torque: Torque = Field(gt=0, description="C0, torque at standstill (N*m)")
    no_load_speed: AngularSpeed = Field(gt=0, description="omega0, speed of zero torque (rad/s)")
    inertia: Inertia | None = Field(default=None, gt=0)
    rotor_mass: Mass | None = Field(default=None, gt=0)
    radius_of_gyration: Length | None = Field(default=None, gt=0)

    @model_validator(mode="after")
    def _one_inertia(self):
        by_geometry = self.rotor_mass is not None or self.radius_of_gyration is not None
        if self.inertia is not None and by_geometry:
            raise ScenarioError("motor.inertia", "give either inertia or rotor_mass + radius_of_gyration, not both")
        if self.inertia is None and not (self.rotor_mass is not None and self.radius_of_gyration is not None):
            missing = "motor.inertia" if not by_geometry else (
                "motor.radius_of_gyration" if self.rotor_mass is not None else "motor.rotor_mass")
            raise ScenarioError(missing, "required: the motor's inertia, or its rotor_mass and radius_of_gyration")
        return self

    @property
    def moment_of_inertia(self) -> float:
        if self.inertia is not None:
            return self.inertia
        return self.rotor_mass * self.radius_of_gyration**2


class ClutchSpec(Section):
    inner_radius: Length = Field(gt=0)
    outer_radius: Length = Field(gt=0)
    half_angle: Angle = Field(gt=0, lt=math.pi / 2, description="cone half-angle beta (rad)")
    static_friction: Number = Field(gt=0)
    kinetic_friction: Number = Field(ge=0)
    surfaces: int = Field(default=1, ge=1, strict=True)
    engagement_force: EngagementForce
    mean_radius: Literal["uniform_wear", "uniform_pressure"] = "uniform_wear"
    driving_inertia: Inertia = Field(default=0.0, ge=0, description="clutch half on the motor shaft")
    driven_inertia: Inertia = Field(default=0.0, ge=0, description="clutch half on the pinion shaft")

    @model_validator(mode="after")
    def _consistent(self):
        if self.kinetic_friction > self.static_friction:
            raise ScenarioError(
                "clutch.kinetic_friction",
                f"kinetic friction {self.kinetic_friction:g} exceeds static friction {self.static_friction:g}",
            )
        if self.inner_radius >= self.outer_radius:
            raise ScenarioError(
                "clutch.inner_radius",
                f"inner radius {self.inner_radius:g} m must be smaller than outer radius {self.outer_radius:g} m",
            )
        return self


class GearSpec(Section):
    pinion_teeth: int = Field(ge=1, strict=True)
    wheel_teeth: int = Field(ge=1, strict=True)
    module: Length = Field(gt=0)
    pressure_angle: Angle = Field(default=math.radians(20.0), gt=0, lt=math.pi / 2)
    pinion_inertia: Inertia = Field(default=0.0, ge=0)
    wheel_inertia: Inertia = Field(default=0.0, ge=0)


class DrumSpec(Section):
    diameter: Length = Field(gt=0)
    inertia: Inertia = Field(gt=0)


class LoadSpec(Section):
    mass: Mass = Field(ge=0)


class InitialSpec(Section):
    motor_speed: AngularSpeed = 0.0
    drum_speed: AngularSpeed = 0.0


class BrakeSpec(Section):
    release_time: Time = Field(ge=0, description="the holding brake frees the drum at this time (s)")


class BearingsSpec(Section):
    gear_offset: Length = Field(gt=0, description="a: bearing A to the gear, away from B")
    rope_offset: Length = Field(gt=0, description="bearing A to the rope, towards B")
    span: Length = Field(gt=0, description="bearing A to bearing B")


class SimulationSpec(Section):
    duration: Time = Field(gt=0)
    output_interval: Time = Field(gt=0)
    rtol: Number = Field(default=1e-8, gt=0, lt=1)
    atol: Number = Field(default=1e-10, gt=0)
    solver: Literal[SOLVERS] = "tsit5"  # type: ignore[valid-type]
    max_switches: int = Field(default=200, ge=1, strict=True,
                              description="mode switches allowed before a run is declared chattering")

    @model_validator(mode="after")
    def _grid(self):
        if self.output_interval > self.duration:
            raise ScenarioError(
                "simulation.output_interval",
                f"{self.output_interval:g} s is longer than the duration {self.duration:g} s",
            )
        if self.duration / self.output_interval > 2_000_000:
            raise ScenarioError(
                "simulation.output_interval",
                f"{self.duration / self.output_interval:.3g} output rows; at most 2e6 are allowed",
            )
        return self


class Scenario(Section):
    name: str = Field(min_length=1)
    description: str = ""
    motor: MotorSpec
    clutch: ClutchSpec
    gears: GearSpec
    drum: DrumSpec
    load: LoadSpec
    gravity: Acceleration = Field(default=9.81, ge=0)
    initial: InitialSpec = InitialSpec()
    brake: BrakeSpec | None = None
    bearings: BearingsSpec | None = None
    simulation: SimulationSpec
    sweep: dict[str, list[Any]] | None = None

    _raw: dict = PrivateAttr(default_factory=dict)
    _text: str = PrivateAttr(default="")
    _source: str = PrivateAttr(default="<scenario>")

    @model_validator(mode="after")
    def _brake_holds_still_drum(self):
        if self.brake is not None and self.initial.drum_speed != 0.0:
            raise ScenarioError(
                "initial.drum_speed",
                "must be 0 when a holding brake (brake:) keeps the drum still at the start",
            )
        return self

    @property
    def text(self) -> str:
        """The scenario as read, with command-line overrides noted."""
        return self._text

    @property
    def source(self) -> str:
        return self._source

    @property
    def raw(self) -> dict:
        """The scenario as plain data (before unit conversion), overrides applied."""
        return copy.deepcopy(self._raw)

    def resolved(self) -> dict:
        """The scenario in SI numbers, as JSON-friendly data."""
        return json.loads(self.model_dump_json(exclude={"sweep"}))


# --------------------------------------------------------------------------------------
# reading YAML with line numbers


def _yaml() -> YAML:
    yaml = YAML(typ="rt")  # round-trip: keeps line numbers; rejects duplicate keys
    yaml.allow_duplicate_keys = False
    return yaml


def _read_yaml(text: str, source: str) -> CommentedMap:
    try:
        data = _yaml().load(io.StringIO(text))
    except MarkedYAMLError as exc:
        mark = exc.problem_mark or exc.context_mark
        line = mark.line + 1 if mark is not None else None
        problem = (exc.problem or exc.context or "malformed YAML").strip()
        key = ""
        if "duplicate key" in problem or "found duplicate key" in str(exc):
            problem = "duplicate key " + _duplicate_name(str(exc))
        raise ScenarioError(key, f"malformed YAML: {problem}", source=source, line=line) from None
    except Exception as exc:  # ruamel's other errors (e.g. reader errors on binary data)
        raise ScenarioError("", f"malformed YAML: {str(exc).splitlines()[0]}", source=source) from None
    if data is None:
        raise ScenarioError("", "the scenario is empty", source=source)
    if not isinstance(data, dict):
        raise ScenarioError("", "a scenario must be a mapping of sections (name:, motor:, clutch:, ...)",
                            source=source, line=1)
    return data


def _duplicate_name(message: str) -> str:
    for line in message.splitlines():
        if "duplicate key" in line:
            return line.split("duplicate key", 1)[1].strip().rstrip(".")
    return ""


def _line_of(node: Any, path: tuple) -> int | None:
    """Best line (1-based) for a location: the deepest node the path reaches."""
    line = None
    for part in path:
        if isinstance(node, CommentedMap) and part in node:
            pos = node.lc.key(part) if hasattr(node, "lc") else None
            line = pos[0] + 1 if pos else line
            node = node[part]
        elif isinstance(node, CommentedSeq) and isinstance(part, int) and part < len(node):
            pos = node.lc.item(part)
            line = pos[0] + 1 if pos else line
            node = node[part]
        else:
            if isinstance(node, (CommentedMap, CommentedSeq)) and line is None and node.lc.line is not None:
                line = node.lc.line + 1
            break
    return line


def _to_plain(node: Any) -> Any:
    if isinstance(node, dict):
        return {str(k): _to_plain(v) for k, v in node.items()}
    if isinstance(node, (list, tuple)):
        return [_to_plain(v) for v in node]
    if hasattr(node, "__float__") and type(node).__name__.startswith("Scalar"):
        return float(node)
    return node


# --------------------------------------------------------------------------------------
# keys: known paths, near matches, overrides


def _model_of(section: type[BaseModel], name: str) -> type[BaseModel] | None:
    field = section.model_fields.get(name)
    if field is None:
        return None
    for candidate in (field.annotation, *getattr(field.annotation, "__args__", ())):
        if isinstance(candidate, type) and issubclass(candidate, Section):
            return candidate
    return None


def _check_key(dotted: str, origin: str) -> None:
    """Raise unless ``dotted`` names a scalar (or table) key of the schema."""
    model: type[BaseModel] = Scenario
    parts = dotted.split(".")
    for i, part in enumerate(parts):
        if part not in model.model_fields or part == "sweep":
            known = [k for k in model.model_fields if k != "sweep"]
            prefix = ".".join(parts[:i])
            raise ScenarioError(
                ".".join(parts[: i + 1]),
                f"unknown key{_suggest(part, known, prefix)}",
                source=origin,
            )
        sub = _model_of(model, part)
        if i == len(parts) - 1:
            if sub is not None:
                raise ScenarioError(dotted, "is a section; name one of its keys, e.g. "
                                    f"{dotted}.{next(iter(sub.model_fields))}", source=origin)
            return
        if sub is None:
            raise ScenarioError(".".join(parts[: i + 1]), "is a value, not a section", source=origin)
        model = sub


def _suggest(word: str, choices: list[str], prefix: str = "") -> str:
    near = difflib.get_close_matches(word, choices, n=1, cutoff=0.6)
    if near:
        full = f"{prefix}.{near[0]}" if prefix else near[0]
        return f" (did you mean {full}?)"
    where = f" in {prefix}" if prefix else ""
    return f"; known keys{where}: {', '.join(choices)}"


def parse_override(assignment: str) -> tuple[str, Any]:
    """``"clutch.engagement_force=2500 N"`` -> (key, value); the value is read as YAML."""
    if "=" not in assignment:
        raise ScenarioError("--set", f"expected KEY=VALUE, got {assignment!r}")
    key, text = assignment.split("=", 1)
    key = key.strip()
    try:
        value = _to_plain(_yaml().load(io.StringIO(text))) if text.strip() else None
    except MarkedYAMLError:
        value = text.strip()
    if value is None:
        raise ScenarioError(key, f"--set needs a value, got {assignment!r}")
    return key, value


def _assign(raw: dict, dotted: str, value: Any) -> None:
    node = raw
    parts = dotted.split(".")
    for part in parts[:-1]:
        if not isinstance(node.get(part), dict):
            node[part] = {}
        node = node[part]
    node[parts[-1]] = value


# --------------------------------------------------------------------------------------
# loading


def load_scenario(source: str | Path, overrides: list[str] | dict[str, Any] | None = None) -> Scenario:
    """Read and validate a scenario file, with optional ``dotted.key=value`` overrides."""
    path = Path(source)
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise ScenarioError("", "no such scenario file", source=str(source)) from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ScenarioError("", f"cannot read the scenario: {exc}", source=str(source)) from None
    return scenario_from_text(text, source=str(source), overrides=overrides)


def scenario_from_text(text: str, source: str = "<scenario>",
                       overrides: list[str] | dict[str, Any] | None = None) -> Scenario:
    tree = _read_yaml(text, source)
    raw = _to_plain(tree)
    pairs = list(overrides.items()) if isinstance(overrides, dict) else [
        parse_override(item) for item in (overrides or [])
    ]
    for key, value in pairs:
        _check_key(key, "--set")
        _assign(raw, key, value)
    if pairs:
        text = text.rstrip("\n") + "\n# overrides from the command line:\n" + "".join(
            f"#   --set {k}={json.dumps(v)}\n" for k, v in pairs)
    return _validate(raw, tree, text, source, overridden={k for k, _ in pairs})


def scenario_from_dict(data: dict, name: str = "<dict>") -> Scenario:
    """Validate a scenario given as Python data (tests, notebooks)."""
    import ruamel.yaml

    buffer = io.StringIO()
    ruamel.yaml.YAML().dump(data, buffer)
    return scenario_from_text(buffer.getvalue(), source=name)


def _validate(raw: dict, tree: Any, text: str, source: str, overridden: set[str] = frozenset()) -> Scenario:
    try:
        scenario = Scenario.model_validate(raw)
    except ValidationError as exc:
        err = exc.errors()[0]
        loc = tuple(p for p in err["loc"] if not (isinstance(p, str) and p.startswith(("function-", "tagged-union"))))
        # pydantic adds the union branch name to locations; keep the user's path only
        loc = tuple(p for p in loc if p not in ("float", "list[tuple[float,float]]", "ForceTable"))
        raise _error_from(err, loc, tree, source, overridden) from None
    except ScenarioError as exc:
        exc.source = "--set" if exc.key in overridden else source
        exc.line = None if exc.key in overridden else _line_of(tree, tuple(exc.key.split(".")))
        raise exc from None
    if scenario.sweep:
        for key, values in scenario.sweep.items():
            try:
                _check_key(key, source)
            except ScenarioError as exc:
                exc.key = f"sweep.{exc.key}"
                exc.line = _line_of(tree, ("sweep", key))
                raise
            if not isinstance(values, list) or not values:
                raise ScenarioError(f"sweep.{key}", "needs a non-empty list of values",
                                    source=source, line=_line_of(tree, ("sweep", key)))
    scenario._raw = raw
    scenario._text = text
    scenario._source = source
    return scenario


def _error_from(err: dict, loc: tuple, tree: Any, source: str, overridden: set[str]) -> ScenarioError:
    key = ".".join(str(p) for p in loc)
    kind = err["type"]
    if kind == "extra_forbidden":
        parent = loc[:-1]
        model: type[BaseModel] = Scenario
        for part in parent:
            model = _model_of(model, str(part)) or model
        known = list(model.model_fields)
        message = "unknown key" + _suggest(str(loc[-1]), known, ".".join(map(str, parent)))
    elif kind == "missing":
        message = "required section is missing" if len(loc) == 1 and loc[0] in Scenario.model_fields and \
            _model_of(Scenario, loc[0]) is not None else "required value is missing"
    elif kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        bound = err["ctx"]
        message = f"{err['msg'].lower()}, got {err['input']!r}"
        del bound
    elif kind == "finite_number":
        message = f"must be a finite number, got {err['input']!r}"
    else:
        message = err["msg"].removeprefix("Value error, ")
        if kind in ("int_type", "int_from_float", "int_parsing"):
            message = f"must be a whole number, got {err['input']!r}"
        elif kind == "literal_error":
            message = f"{message.replace('Input should be', 'must be')}, got {err['input']!r}"
    origin = "--set" if key in overridden else source
    line = None if key in overridden else _line_of(tree, loc)
    return ScenarioError(key, message, source=origin, line=line)


# --------------------------------------------------------------------------------------
# sweeps


def sweep_values(scenario: Scenario) -> list[tuple[str, Scenario]]:
    """One (label, scenario) per run: the sweep's values, a grid when two keys are swept."""
    if not scenario.sweep:
        return [("", scenario)]
    keys = list(scenario.sweep)
    runs = []
    for combo in itertools.product(*(scenario.sweep[k] for k in keys)):
        raw = scenario.raw
        raw.pop("sweep", None)
        for key, value in zip(keys, combo):
            _assign(raw, key, value)
        label = ", ".join(f"{k}={_format_value(v)}" for k, v in zip(keys, combo))
        try:
            run = _validate(raw, None, scenario.text, scenario.source)
        except ScenarioError as exc:
            exc.message = f"{exc.message} (in sweep run {label})"
            exc.line = None
            raise
        runs.append((label, run))
    return runs


def _format_value(value: Any) -> str:
    if isinstance(value, list):
        return json.dumps(value, separators=(",", ":"))
    return str(value)

"""Tables in scenario files: rows of quantities checked and converted to SI.

The engagement force against time (a step where a time repeats), a motor's
torque against speed, one period of a torque ripple against angle, a friction
coefficient against temperature: each row read by :mod:`.units`, the rows
checked as a whole (the first column increasing), and the pydantic field types
of the schema built on them.  A bad row is a :class:`TableError` that names it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Annotated, Any

from pydantic import BaseModel, BeforeValidator, ConfigDict

from .units import (
    ANGLE,
    ANGULAR_SPEED,
    DIMENSIONLESS,
    FORCE,
    TEMPERATURE,
    TIME,
    TORQUE,
    VELOCITY,
    Dimension,
    UnitError,
    check_range,
    metadata_of,
    show,
    to_si,
)


class TableError(UnitError):
    """A bad row of a table; ``row`` is its index from 0."""

    def __init__(self, row: int, message: str):
        super().__init__(f"row {row + 1}: {message}")
        self.row = row


def force_table(value: object) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Engagement force: a constant, or rows ``[time, force]``; a time may repeat once (a step).

    Returns the times (s) and forces (N); a constant holds from t = 0.
    """
    if not isinstance(value, (list, tuple)):
        try:
            force = to_si(value, FORCE)
        except UnitError as exc:
            raise UnitError(f"{exc}; or a table [[time, force], ...]") from None
        check_range(force, value, FORCE, ge=0, hint=" (a clutch cannot be pushed apart)")
        return (0.0,), (force,)
    if not value:
        raise UnitError("the table is empty; give rows [time, force], like [[0 s, 0 N], [0.5 s, 3000 N]]")

    def force(entry):
        return check_range(to_si(entry, FORCE), entry, FORCE, ge=0, hint=" (a clutch cannot be pushed apart)")

    return time_rows(value, FORCE, "[0.5 s, 3000 N]", force)


def time_rows(value: list, dimension: Dimension, example: str, read=None
              ) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """Rows ``[time, value]`` of a table of time: times from 0 s, never going back, each at most twice (a
    step); ``read`` converts and checks a value (default: to SI in ``dimension``)."""
    times: list[float] = []
    values: list[float] = []
    for i, row in enumerate(value):
        if not isinstance(row, (list, tuple)) or len(row) != 2:
            raise TableError(i, f"must be a pair [time, {dimension.name}], like {example}, got {row!r}")
        try:
            t = check_range(to_si(row[0], TIME), row[0], TIME, ge=0, hint=" (the run starts at 0 s)")
            v = read(row[1]) if read is not None else to_si(row[1], dimension)
        except UnitError as exc:
            raise TableError(i, str(exc)) from None
        if times and t < times[-1]:
            raise TableError(i, f"time goes backwards ({t:g} s after {times[-1]:g} s)")
        if len(times) >= 2 and t == times[-1] == times[-2]:
            raise TableError(i, f"a time may appear at most twice (a step); {t:g} s appears three times")
        times.append(t)
        values.append(v)
    return tuple(times), tuple(values)


def pair_table(value: object, first: Dimension, second: Dimension, what: str, example: str
               ) -> tuple[tuple[float, float], ...]:
    """Rows ``[first, second]``, at least two, the first column strictly increasing (``what`` names it)."""
    if not isinstance(value, (list, tuple)) or len(value) < 2:
        raise UnitError(f"must be a table of at least two rows [{first.name}, {second.name}], {example}")
    rows: list[tuple[float, float]] = []
    for i, row in enumerate(value):
        if not isinstance(row, (list, tuple)) or len(row) != 2:
            raise TableError(i, f"must be a pair [{first.name}, {second.name}], {example}, got {row!r}")
        try:
            x, y = to_si(row[0], first), to_si(row[1], second)
        except UnitError as exc:
            raise TableError(i, str(exc)) from None
        if rows and x <= rows[-1][0]:
            raise TableError(i, f"{what} must increase ({show(x, first)} after {show(rows[-1][0], first)})")
        rows.append((x, y))
    return tuple(rows)


def friction_temperature_table(value: object, positive: bool) -> tuple[tuple[float, float], ...]:
    """A friction coefficient against the surfaces' temperature: rows ``[temperature, friction]``,
    temperatures strictly increasing and above absolute zero, each friction positive (a static
    coefficient) or at least not negative (a kinetic one)."""
    rows = pair_table(value, TEMPERATURE, DIMENSIONLESS, "temperatures", "like [[25 degC, 0.3], [300 degC, 0.22]]")
    for i, (temperature, friction) in enumerate(rows):
        try:
            check_range(temperature, value[i][0], TEMPERATURE, gt=0)
            check_range(friction, value[i][1], DIMENSIONLESS, **({"gt": 0.0} if positive else {"ge": 0.0}))
        except UnitError as exc:
            raise TableError(i, str(exc)) from None
    return rows


def torque_speed_table(value: object) -> tuple[tuple[float, float], ...]:
    """A motor characteristic: rows ``[speed, torque]``, at least two, speeds strictly increasing."""
    return pair_table(value, ANGULAR_SPEED, TORQUE, "speeds", "like [[0 rpm, 500 N*m], [300 rpm, 0 N*m]]")


def slip_speed_table(value: object, second: Dimension, what: str, example: str,
                     speed: Dimension = ANGULAR_SPEED) -> tuple[tuple[float, float], ...]:
    """A friction against the slip speed: rows ``[speed, value]``, at least two, speeds rising from zero or
    more (the friction at a slip either way: its speed's size), each value not negative (``what`` names it);
    ``speed`` the slip's dimension (a line's: a velocity)."""
    rows = pair_table(value, speed, second, "speeds", example)
    for i, (slip, friction) in enumerate(rows):
        try:
            check_range(slip, value[i][0], speed, ge=0, hint=" (a slip speed's size)")
            check_range(friction, value[i][1], second, ge=0, hint=f" ({what} opposes the slip)")
        except UnitError as exc:
            raise TableError(i, str(exc)) from None
    return rows


def angle_torque_table(value: object) -> tuple[tuple[float, float], ...]:
    """One period of a torque ripple: rows ``[angle, torque]``, angles strictly increasing."""
    return pair_table(value, ANGLE, TORQUE, "angles", "like [[0 deg, 0 N*m], [90 deg, 850 N*m], [360 deg, 0 N*m]]")


# the value types of the schema (pydantic fields)


@dataclass(frozen=True)
class FirstColumn:
    """Metadata of a table field: the dimension of its rows' first entries (for the bare-number note)."""

    dimension: Dimension


@dataclass(frozen=True)
class Columns:
    """Metadata of a table field: each column's name and dimension, for the scenario reference."""

    columns: tuple[tuple[str, Dimension], ...]


def first_column_of(field) -> Dimension | None:
    """The dimension of a table field's first column (a FirstColumn in its metadata), or None."""
    found = metadata_of(field, FirstColumn)
    return found.dimension if found is not None else None


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


def _to_force_table(value: Any) -> ForceTable:
    if isinstance(value, ForceTable):
        return value
    times, forces = force_table(value)
    return ForceTable(times=times, forces=forces)


EngagementForce = Annotated[ForceTable, BeforeValidator(_to_force_table), FORCE,  # swept as its force
                            Columns((("time", TIME), ("force", FORCE)))]
TorqueSpeedTable = Annotated[tuple[tuple[float, float], ...], BeforeValidator(
    lambda value: value if isinstance(value, tuple) else torque_speed_table(value)),
    Columns((("speed", ANGULAR_SPEED), ("torque", TORQUE)))]
_FRICTION_COLUMNS = Columns((("temperature", TEMPERATURE), ("friction coefficient", DIMENSIONLESS)))
StaticFrictionTable = Annotated[tuple[tuple[float, float], ...], BeforeValidator(
    lambda value: value if isinstance(value, tuple) else friction_temperature_table(value, positive=True)),
    FirstColumn(TEMPERATURE), _FRICTION_COLUMNS]
KineticFrictionTable = Annotated[tuple[tuple[float, float], ...], BeforeValidator(
    lambda value: value if isinstance(value, tuple) else friction_temperature_table(value, positive=False)),
    FirstColumn(TEMPERATURE), _FRICTION_COLUMNS]


def constant_or_slip_table(dimension: Dimension, what: str, example: str, speed: Dimension = ANGULAR_SPEED):
    """A field given as a constant not below zero, or as a table of the slip speed (rows [speed, value]): a float
    or the table's rows (``what`` names the value, ``example`` a table, ``speed`` the slip's dimension)."""

    def convert(value: Any):
        if isinstance(value, tuple):  # already read
            return value
        if isinstance(value, list):
            return slip_speed_table(value, dimension, what, example, speed)
        try:
            number = to_si(value, dimension)
        except UnitError as exc:
            raise UnitError(f"{exc}; or a table of the slip speed [[speed, {dimension.name}], ...], {example}") from None
        return check_range(number, value, dimension, ge=0, hint=f" ({what} opposes the slip)")

    return Annotated[float | tuple[tuple[float, float], ...], BeforeValidator(convert), dimension,
                     FirstColumn(speed), Columns((("slip speed", speed), (what.split(" ", 1)[1], dimension)))]


SlipFriction = constant_or_slip_table(DIMENSIONLESS, "a friction coefficient", "like [[0 rad/s, 0.5], [10 rad/s, 0.4]]")
SlipTorque = constant_or_slip_table(TORQUE, "a friction torque", "like [[0 rad/s, 2 N*m], [100 rad/s, 3 N*m]]")
SlipForce = constant_or_slip_table(FORCE, "a friction force", "like [[0 m/s, 15 N], [12 m/s, 13 N]]", VELOCITY)
AngleTorqueTable = Annotated[tuple[tuple[float, float], ...], BeforeValidator(
    lambda value: value if isinstance(value, tuple) else angle_torque_table(value)),
    Columns((("angle", ANGLE), ("torque", TORQUE)))]

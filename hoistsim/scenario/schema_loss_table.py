"""A lossy gear stage's loss table (``drivetrain.gears.<stage>.loss_table``): Modelica's LossyGear lossTable.

Rows ``[speed, efficiency when the input drives, efficiency when the output drives, bearing friction torque when
the input drives, when the output drives]``, read at the size of the input shaft's speed: Modelica's
``[|w_a|, eta_mf1, eta_mf2, |tau_bf1|, |tau_bf2|]``, the bearing friction torques resultant at the input shaft.
"""

from __future__ import annotations

from typing import Annotated

from pydantic import BeforeValidator

from .tables import FirstColumn, TableError
from .units import ANGULAR_SPEED, DIMENSIONLESS, TORQUE, UnitError, check_range, show, to_si

_COLUMNS = ("speed", "input-driving efficiency", "output-driving efficiency", "input-driving bearing torque",
            "output-driving bearing torque")
_EXAMPLE = "like [[0 rad/s, 0.5, 0.5, 0 N*m, 0 N*m]]"


def loss_table(value: object) -> tuple[tuple[float, float, float, float, float], ...]:
    """Rows of five: the speed (the first 0, then rising), two efficiencies in (0, 1], two torques not negative.
    With both efficiencies 1 a row's two torques must agree: an ideal mesh passes the same torque whichever side
    drives, so its bearings cannot lose more one way (Modelica's split of them is arbitrary there)."""
    if not isinstance(value, (list, tuple)) or not value:
        raise UnitError(f"must be a table of rows [speed, efficiency input drives, efficiency output drives, "
                        f"bearing torque input drives, bearing torque output drives], {_EXAMPLE}")
    rows: list[tuple[float, ...]] = []
    for i, row in enumerate(value):
        if not isinstance(row, (list, tuple)) or len(row) != 5:
            raise TableError(i, f"must be a row of five [{', '.join(_COLUMNS)}], {_EXAMPLE}, got {row!r}")
        try:
            speed = check_range(to_si(row[0], ANGULAR_SPEED), row[0], ANGULAR_SPEED, ge=0.0,
                                hint=" (the table is read at the size of the input's speed)")
            efficiencies = [check_range(to_si(v, DIMENSIONLESS), v, DIMENSIONLESS, gt=0.0, le=1.0,
                                        hint=f" ({name})") for v, name in zip(row[1:3], _COLUMNS[1:3])]
            torques = [check_range(to_si(v, TORQUE), v, TORQUE, ge=0.0, hint=f" ({name}: it opposes the motion)")
                       for v, name in zip(row[3:5], _COLUMNS[3:5])]
        except UnitError as exc:
            raise TableError(i, str(exc)) from None
        if i == 0 and speed != 0.0:
            raise TableError(i, f"the speeds start at 0 rad/s (the gear at rest reads the first row), got "
                                f"{show(speed, ANGULAR_SPEED)}")
        if rows and speed <= rows[-1][0]:
            raise TableError(i, f"speeds must rise ({show(speed, ANGULAR_SPEED)} after "
                                f"{show(rows[-1][0], ANGULAR_SPEED)})")
        if efficiencies == [1.0, 1.0] and torques[0] != torques[1]:
            raise TableError(i, "with both efficiencies 1 the two bearing torques must be equal (an ideal mesh "
                                f"passes the same torque whichever side drives), got {torques[0]:g} and "
                                f"{torques[1]:g} N*m")
        rows.append((speed, *efficiencies, *torques))
    return tuple(rows)


LossTable = Annotated[tuple[tuple[float, float, float, float, float], ...], BeforeValidator(
    lambda value: value if isinstance(value, tuple) else loss_table(value)), FirstColumn(ANGULAR_SPEED)]

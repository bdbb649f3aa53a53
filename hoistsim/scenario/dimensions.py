"""What a scenario key measures: each quantity's dimension, its SI unit and an example (:mod:`.units` reads
values in them)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Dimension:
    """What a scenario key measures: a readable name, its SI unit, an example."""

    name: str
    si_unit: str
    example: str
    radians: int = 0  # power of the angle in the unit ("rpm" is rad/s: 1)
    shown_in: str = ""  # unit for limits in messages, when not the SI one
    # what the key measures where its part is on a line, between masses (a stiffness in N/m where it is
    # torsional between shafts): a value of either kind is read, and the drivetrain checks which its part needs
    line: "Dimension | None" = None
    shafts: "Dimension | None" = None  # with ``line``: the dimension between shafts alone

    def on_line(self, line: "Dimension") -> "Dimension":
        """This dimension, or ``line``'s where the part is on a line (:attr:`line`)."""
        return Dimension(f"{self.name} (between masses: {line.name})", self.si_unit,
                         f"{self.example} or {line.example}", self.radians, self.shown_in, line=line, shafts=self)

    @property
    def rotational(self) -> "Dimension":
        """The dimension alone, without its line's counterpart."""
        return self if self.shafts is None else self.shafts

TORQUE = Dimension("torque", "N*m", "'500 N*m'")
ANGULAR_SPEED = Dimension("angular speed", "rad/s", "'300 rpm'", radians=1, shown_in="rpm")
INERTIA = Dimension("moment of inertia", "kg*m^2", "'40 kg*m^2'")
MASS = Dimension("mass", "kg", "'500 kg'")
LENGTH = Dimension("length", "m", "'20 cm'")
ANGLE = Dimension("angle", "rad", "'25 deg'", radians=1, shown_in="deg")
ANGULAR_ACCELERATION = Dimension("angular acceleration", "rad/s^2", "'1 rad/s^2'", radians=1)
FORCE = Dimension("force", "N", "'200 daN'")
TIME = Dimension("time", "s", "'0.5 s'")
ACCELERATION = Dimension("acceleration", "m/s^2", "'9.81 m/s^2'")
DIMENSIONLESS = Dimension("pure number", "", "0.3")
DENSITY = Dimension("density", "kg/m^3", "'7200 kg/m^3'")
TEMPERATURE = Dimension("temperature", "K", "'25 degC'", shown_in="degC")  # absolute: degC and degF are offsets
HEAT_CAPACITY = Dimension("heat capacity", "J/K", "'2.4 kJ/K'")
CONDUCTANCE = Dimension("thermal conductance", "W/K", "'20 W/K'")
STIFFNESS = Dimension("stiffness", "N/m", "'2.5e5 N/m'")
PRESSURE = Dimension("modulus (a pressure)", "Pa", "'100 GPa'")
AREA = Dimension("area", "m^2", "'95 mm^2'")
FREQUENCY = Dimension("frequency", "Hz", "'5 Hz'")
POWER = Dimension("power", "W", "'15 kW'")
TORSIONAL_STIFFNESS = Dimension("torsional stiffness", "N*m/rad", "'1e4 N*m/rad'", radians=-1)
TORSIONAL_DAMPING = Dimension("torsional damping", "N*m*s/rad", "'10 N*m*s/rad'", radians=-1)
VELOCITY = Dimension("velocity", "m/s", "'1.2 m/s'")
DAMPING = Dimension("damping", "N*s/m", "'25 N*s/m'")

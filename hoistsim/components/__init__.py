"""The parts' textbook formulas from their geometry, in SI units: the lowest layer above the foundation.

A cone clutch's torque per newton, a gear pair's ratio and tooth forces, the drum's rope radius,
the load's weight, the drum shaft's bearing reactions, the linear motor's characteristic.  The
elements and the references both build on these, so each formula is written once.

May import: nothing of hoistsim.
"""

from .clutch import ConeClutch as ConeClutch
from .drum import Drum as Drum
from .drum_shaft import DrumShaft as DrumShaft
from .gears import GearPair as GearPair
from .load import HangingLoad as HangingLoad
from .motor import LinearMotor as LinearMotor

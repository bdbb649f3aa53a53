"""Physics of each machine element from its geometry, in SI units."""

from .clutch import ConeClutch as ConeClutch
from .drum import Drum as Drum
from .gears import GearPair as GearPair
from .load import HangingLoad as HangingLoad
from .motor import LinearMotor as LinearMotor

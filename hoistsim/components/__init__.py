"""Physics of each machine element from its geometry, in SI units."""

from .clutch import ConeClutch as ConeClutch
from .drum import Drum as Drum
from .drum_shaft import DrumShaft as DrumShaft
from .gears import GearPair as GearPair
from .load import HangingLoad as HangingLoad
from .motor import LinearMotor as LinearMotor

"""What every motor characteristic shares: the rotor's inertia and a torque at a speed."""

from __future__ import annotations

import abc

from ..._pytree import pytree_dataclass
from ..core.element import abstract_methods


@pytree_dataclass
class AbstractMotor:
    """A motor's characteristic, the law of the motor element (:mod:`.motor`): its torque at a shaft speed
    and its rotor's inertia; subclasses give the law, each a pytree of its numbers."""

    inertia: object  # kg*m^2, rotor and whatever else turns with it

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        missing = abstract_methods(cls)
        if missing and not cls.__name__.startswith("Abstract"):
            raise TypeError(f"{cls.__name__} lacks {', '.join(missing)}: a motor characteristic must define them")
        pytree_dataclass(cls)

    @abc.abstractmethod
    def characteristic(self, speed):
        """Motor torque (N*m) at shaft speed ``speed`` (rad/s)."""

    @classmethod
    @abc.abstractmethod
    def characteristic_from(cls, spec) -> dict:
        """The characteristic's fields from the motor's keys."""

    def speed_scale(self):
        """A speed (rad/s) typical of the motor, for the slip resolution (None: none of its own)."""
        return None

"""The winch drum on the drum shaft."""

from __future__ import annotations

from typing import ClassVar

from ..core.element import AbstractElement


class Drum(AbstractElement):
    """The drum's inertia on the drum shaft, and the drum speed as an output."""

    inertia: object  # I, kg*m^2

    section: ClassVar[str] = "drum"
    summaries: ClassVar[dict] = {"final_drum_speed": "rad/s"}
    columns: ClassVar[dict] = {"drum_speed": ("rad/s", "drum speed, positive when the load goes up")}

    @classmethod
    def from_spec(cls, spec, scenario) -> "Drum":
        return cls(inertia=spec.inertia)

    def inertias(self) -> tuple:
        return (("drum", self.inertia),)

    def outputs(self, x) -> dict:
        return {"drum_speed": x.speed("drum")}

    def summary(self, x) -> dict:
        return {"final_drum_speed": x.speed("drum")}

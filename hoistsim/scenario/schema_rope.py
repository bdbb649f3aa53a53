"""The schema of the rope and the ground: an elastic rope from the drum to the load, and the load resting
on the ground at the start (values in SI)."""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from . import plausible
from . import units as u
from .schema_base import Section


class RopeSpec(Section):
    """An elastic rope from the drum to the load: a stiffness, or a wire rope's modulus, area and length."""

    alternatives = (("stiffness", "modulus + metallic_area + free_length"),)
    stiffness: u.quantity(u.STIFFNESS, gt=0.0) | None = Field(None, description="k, the rope's")
    modulus: u.quantity(u.PRESSURE, gt=0.0) | None = Field(None, description="E of the rope (steel wire rope: "
                                                           "80-110 GPa): k = E A / L")
    metallic_area: u.quantity(u.AREA, plausible=plausible.WIRE_ROPE_METALLIC_AREA, gt=0.0) | None = Field(
        None, description="A: the wires' cross-section")
    free_length: u.quantity(u.LENGTH, plausible=plausible.ROPE_FREE_LENGTH, gt=0.0) | None = Field(
        None, description="L: drum to load at t = 0")
    damping_ratio: u.quantity(u.DIMENSIONLESS, ge=0.0) = Field(0.0, description="zeta: c = 2 zeta sqrt(k M), k "
                                                               "at t = 0")
    initial_slack: u.quantity(u.LENGTH, ge=0.0) = Field(0.0, description="rope paid out beyond taut at t = 0")

    @model_validator(mode="after")
    def _one_stiffness(self):
        self._one_value_or_group(
            "rope", "stiffness", ("modulus", "metallic_area", "free_length"),
            both="stiffness or a wire rope's modulus, metallic_area and free_length",
            required="the rope's stiffness, or its modulus, metallic_area and free_length")
        return self

    @property
    def characteristic(self) -> str:
        """Which variant: ``stiffness`` (constant) or ``modulus`` (E A / L, L the free length)."""
        return "stiffness" if self.stiffness is not None else "modulus"


class GroundSpec(Section):
    """The load starts resting on the ground, which holds it up and never down."""

    hoisting_class: Literal["HC1", "HC2", "HC3", "HC4"] | None = Field(None, description="EN 13001-2's, for its "
                                                                       "dynamic factor phi2 beside the run's")


class BufferSpec(Section):
    """A buffer under the load at the end of its travel (a pit's, a shaft's bottom): a spring and a damper that
    push the load up once it has come down ``clearance`` below its start, and never pull (Modelica's ElastoGap:
    the damping's push never more than the spring's).  The load on an elastic rope (``rope:``), which goes slack
    as the buffer stops it."""

    clearance: u.quantity(u.LENGTH, gt=0.0) = Field(description="how far below its start the load meets the "
                                                    "buffer's top")
    stiffness: u.quantity(u.STIFFNESS, gt=0.0) = Field(description="k_b, the buffer's spring")
    damping: u.quantity(u.DAMPING, ge=0.0) = Field(0.0, description="d_b, its damper")

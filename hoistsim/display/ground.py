"""The ground under the load: the phase it rests there, when it lifts off."""

from __future__ import annotations

from .panel import Display, Phase


def _headline(summary: dict) -> str | None:
    lift_off = float(summary["lift_off_time"])
    return "load never lifts off" if lift_off != lift_off else f"lifts off at {lift_off:.3f} s"


GROUND = Display(shading=(Phase("load on the ground", "load_on_ground", 1, "#8c510a", hatch="xx"),),
                 headline=_headline)

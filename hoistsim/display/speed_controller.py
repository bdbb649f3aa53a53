"""A drawn drivetrain's speed controllers: the speed each asks for beside the shafts' speeds, and the torque
each drives with against its limits."""

from __future__ import annotations

import numpy as np

from .panel import Display, Panel, SummaryPanel, Trace, drawn_parts


def _limit(name: str, key: str, default_sign: float = 1.0):
    """A limit across the run (N*m): the controller's max_torque, or its min_torque (default -max_torque)."""
    def line(run):
        spec = run["parameters"]["drivetrain"]["speed_controllers"][name]
        value = spec.get(key)
        value = default_sign * spec["max_torque"] if value is None else value
        return np.full(np.shape(run[f"{name}_output"]), value)
    return line


def _panels_for(run: dict) -> tuple:
    controllers = drawn_parts(run, "speed_controllers")
    if not controllers:
        return ()
    references = tuple(Trace(f"{name} reference", f"{name}_reference", style="--") for name in controllers)
    outputs = tuple(trace for name in controllers for trace in (
        Trace(name, f"{name}_torque"),
        Trace(f"{name} limits", f"{name}_output", style=":", limit=True, value=_limit(name, "max_torque")),
        Trace(f"{name} limits", f"{name}_output", style=":", limit=True, value=_limit(name, "min_torque", -1.0))))
    return (Panel("shaft_speeds", "shaft speed [rad/s]", 0, references, height=1.5),
            Panel("controller_outputs", "controller\ntorque [N*m]", 8, outputs, zero_line=True, height=0.8))


def _headline(summary: dict) -> str | None:
    """How long each controller drove at a limit (its torque all it may give), and from when."""
    said = []
    for key, value in summary.items():
        if not key.endswith("_saturated_time"):
            continue
        name, time = key[: -len("_saturated_time")], float(value)
        if not time > 0:
            said.append(f"{name} within its limits")
            continue
        events = summary.get("events")
        first = None if events is None else next((float(row["time"]) for row in events
                                                   if _text(row["kind"]) == f"{name}_saturate"), None)
        said.append(f"{name} at its limit {time:.3f} s" + (f" (from {first:.3f} s)" if first is not None else ""))
    return "; ".join(said + _sequence(summary)) or None


def _distance(metres: float) -> str:
    return f"{metres * 1000:.3g} mm" if abs(metres) < 0.1 else f"{metres:.3g} m"


def _sequence(summary: dict) -> list:
    """A brake sequence's story: when the brake let go and on what torque, how far the load ran back, how long
    and how far an emergency stop took."""
    said = []
    for key in summary:
        if key.endswith("_proven_torque"):
            name = key[: -len("_proven_torque")]
            release, torque = float(summary[f"{name}_release_time"]), float(summary[key])
            said.append(f"brake released at {release:.3f} s on {torque:.4g} N*m" if release == release
                        else "brake never released")
    if "rollback_distance" in summary:
        back = float(summary["rollback_distance"])
        said.append(f"load ran back {_distance(back)}" if back > 1e-6 else "no rollback")
    if "stopping_time" in summary:
        stop = float(summary["stopping_time"])
        distance = summary.get("stopping_distance")
        said.append("emergency stop: " + (f"held after {stop:.3f} s" if stop == stop else "not held by the end")
                    + (f", {_distance(float(distance))} of rope" if distance is not None else ""))
    return said


def _text(value) -> str:
    return value.decode() if isinstance(value, bytes) else str(value)


SPEED_CONTROLLER = Display(panels_for=_panels_for, headline=_headline,
                           summary_panels=(SummaryPanel("rollback_distance", "rollback [mm]", 50, scale=1e3),
                                           SummaryPanel("stopping_distance", "emergency stop:\ndistance [m]", 51),
                                           SummaryPanel("stopping_time", "emergency stop:\ntime [s]", 52)),
                           reads=lambda column: column.endswith(("_reference", "_output", "_integral", "_torque")))

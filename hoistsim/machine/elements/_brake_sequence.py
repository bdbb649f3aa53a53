"""A hoist drive's brake sequence, as its speed controller keeps it: counts of time as states, each starting
where its condition first holds and then running on (so a condition met once stays met: no state jumps), the
conditions' changes located as switches are.

- The release count starts when the drive's torque is proven (its magnitude at the proving torque); the brake
  (:mod:`.operated_brake`) opens when it passes the brake's opening time.
- The close count starts on an emergency stop, or after the stop command once the speed is below the closing
  speed with the brake open; the brake holds again when it passes the brake's closing time.
- The emergency count starts on the emergency stop: at its time, or where the speed first exceeds the trip speed
  (an overspeed trip); from then on the drive is switched off, and the time the brake takes to hold the drum is
  the count's value then (``stopping_time``).
- Where a load hangs from a shaft geared to the one controlled, the rope the drum pays out backwards from the
  release until the drive has the load going its way (the drum first turning forwards, or the reference first
  asking for lowering): ``rollback_distance``; and on an emergency stop, until the brake holds the drum
  (``stopping_distance``, and the time it takes, ``stopping_time``).
"""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from ..core.element import STUCK

ON, STOPPED = 1.0, 0.0


def step_table(at) -> tuple:
    """A table of time stepping from 0 to 1 at ``at`` (None: never): (times, values), three rows either way."""
    if at is None:
        return np.zeros(3), np.zeros(3)
    return np.array([0.0, at, at]), np.array([0.0, 0.0, 1.0])


def counts(name: str) -> tuple:
    """The states: (release count, close count, the count since the drive has the load going its way, the
    rollback, the emergency stop's travel)."""
    return (f"{name}_release_count", f"{name}_close_count", f"{name}_under_way", f"{name}_rollback",
            f"{name}_stopping_travel")


def emergency_count(name: str) -> str:
    """The state of the time since the emergency stop (0 before it)."""
    return f"{name}_emergency_count"


def switched_off(controller, x):
    """Whether the drive is switched off by its emergency stop: since its time, or since its speed first exceeded
    the trip speed (the count running: a condition met once stays met)."""
    tripped = x.table(f"{controller.section}.emergency") > 0.5
    if controller.has_trip:
        tripped = tripped | (jnp.abs(x.speed(controller.measures)) >= controller.trip_speed)
    return tripped | (x.state(emergency_count(controller.section)) > 0.0)


def conditions(controller, x, torque) -> dict:
    """What the sequence's counts and distances turn on, at the instant (``torque``: the drive's on its shaft)."""
    release, close, under_way, _, _ = counts(controller.section)
    speed = x.speed(controller.measures)
    released = x.state(release) >= controller.release_delay
    return {"proven": jnp.abs(torque) >= controller.prove_torque, "released": released,
            "emergency": switched_off(controller, x) if controller.has_emergency_stop else False,
            "stopping": x.table(f"{controller.section}.stopping") > 0.5,
            "slow": jnp.abs(speed) < controller.close_speed,
            "under_way": x.state(under_way) > 0.0 if controller.has_rope else False,
            "held": (x.state(close) >= controller.close_delay) & (x.mode(controller.brake) == STUCK),
            "speed": speed}


def rates(controller, x, torque) -> dict:
    """d/dt of each count (1 while it runs) and of the distances (m/s of rope)."""
    release, close, under_way, rollback, travel = counts(controller.section)
    c = conditions(controller, x, torque)
    running = lambda state, starts: jnp.where((x.state(state) > 0.0) | starts, 1.0, 0.0)  # noqa: E731
    out = {release: running(release, c["proven"] & ~c["emergency"]),
           close: running(close, c["emergency"] | (c["stopping"] & c["slow"] & c["released"]))}
    if controller.has_emergency_stop:
        out[emergency_count(controller.section)] = jnp.where(c["emergency"], 1.0, 0.0)
    if controller.has_rope:
        rope = controller.rope_per_radian * c["speed"]  # m/s of rope, positive lifting
        lowering = controller.reference(x) < 0.0
        out[under_way] = running(under_way, c["released"] & ((c["speed"] > 0.0) | lowering))
        out[rollback] = jnp.where(c["released"] & ~c["under_way"], jnp.maximum(-rope, 0.0), 0.0)
        out[travel] = jnp.where(c["emergency"] & ~c["held"], jnp.abs(rope), 0.0)
    return out


def guard_kinds(controller) -> tuple:
    """The guards' names: the proof, the closing speed, (with a rope) the controlled shaft and the reference
    through rest, and the trip speed (an overspeed trip's)."""
    name = controller.section
    return ((f"{name}_proof", f"{name}_slow") + ((f"{name}_turn", f"{name}_asked") if controller.has_rope else ())
            + ((f"{name}_overspeed",) if controller.has_trip else ()))


def guards(controller, x, torque) -> dict:
    """Where the conditions change: the torque through the proving torque, the speed through the closing speed,
    the controlled shaft and its reference through rest (the rollback's end), the speed through the trip speed."""
    speed = x.speed(controller.measures)
    values = (jnp.abs(torque) - controller.prove_torque, controller.close_speed - jnp.abs(speed))
    values += (speed, controller.reference(x)) if controller.has_rope else ()
    values += (controller.trip_speed - jnp.abs(speed),) if controller.has_trip else ()
    return dict(zip(guard_kinds(controller), values))


def summaries(controller) -> dict:
    name = controller.section
    out = {f"{name}_proven_torque": "N*m", f"{name}_release_time": "s"}
    if controller.has_rope:
        out["rollback_distance"] = "m"
    if controller.has_emergency_stop:
        out["stopping_time"] = "s"
        if controller.has_rope:
            out["stopping_distance"] = "m"
    return out


def extremes(controller, x, torque) -> dict:
    name = controller.section
    c = conditions(controller, x, torque)
    out = {f"{name}_proven_torque": ("first_value", (c["released"], torque)),
           f"{name}_release_time": ("first", c["released"])}
    if controller.has_emergency_stop:
        out["stopping_time"] = ("first_value", (c["emergency"] & c["held"],
                                                x.state(emergency_count(controller.section))))
    return out


def final(controller, x) -> dict:
    _, _, _, rollback, travel = counts(controller.section)
    out = {}
    if controller.has_rope:
        out["rollback_distance"] = x.state(rollback)
        if controller.has_emergency_stop:
            out["stopping_distance"] = x.state(travel)
    return out

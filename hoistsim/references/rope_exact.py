"""Exact piecewise solution of the hoist on an elastic rope, the reference the rope's tests trust.

With the linear motor, the cone clutch locked or slipping (its sliding torque a
linear function of time where the engagement force is), a rope of constant
stiffness and damping, and the load on the ground or in the air, every phase is
an affine linear ODE with constant coefficients, z' = A z, in the augmented
state z = (motor speed, pinion speed, stretch, load speed, load height, t, 1).
Its solution is the matrix exponential z(t) = expm(A (t - t0)) z(t0), and every
switch is a root of a function of that exact trajectory: the clutch's slip or
breakaway, the rope going slack or taut, the load lifting off or landing.  The
roots are bracketed on a fine sampling of the trajectory and refined by Brent's
method to round-off.

Written from the equations (the rope's law in docs/how-to/lift-off.md), not from the elements:
the bodies, the clutch's static check and the rope's law are stated here again.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.linalg import expm
from scipy.optimize import brentq

WM, WP, S, V, X, T, ONE = range(7)
LOCKED, SLIP_FORWARD, SLIP_BACKWARD, OPEN = "locked", "slip+", "slip-", "open"
SIGN = {SLIP_FORWARD: 1.0, SLIP_BACKWARD: -1.0, LOCKED: 0.0, OPEN: 0.0}
# sampling of a phase before its roots are refined (s); far below the rope's period
SAMPLE = 2e-4


@dataclass(frozen=True)
class RopeHoist:
    """The machine in SI: two clutch shafts (the drum side reduced to the pinion), a rope and the load."""

    motor_inertia: float  # J_a, kg*m^2
    output_inertia: float  # J_b: pinion shaft, gears and drum reduced to it, without the load
    stall_torque: float  # C0, N*m
    no_load_speed: float  # omega0, rad/s
    capacity_per_newton: float  # f_a c, m
    sliding_per_newton: float  # f c, m
    lever: float  # r = R / tau: rope speed at the drum per pinion speed, m/rad
    ratio: float  # tau
    mass: float  # M, kg
    gravity: float  # g
    stiffness: float  # k, N/m
    damping: float  # c, N*s/m
    force_times: tuple  # the engagement force, piecewise linear: knots (s) ...
    forces: tuple  # ... and values (N); a repeated time is a step
    on_ground: bool

    @classmethod
    def from_scenario(cls, scenario) -> "RopeHoist":
        """The reduction of a scenario with a linear motor, the cone clutch and a constant-stiffness rope."""
        from .model import Machine

        d = Machine.from_scenario(scenario.model_copy(update={"load": scenario.load.model_copy(
            update={"mass": 0.0})})).reduced()  # the rope's load is a body of its own, not on the drum
        rope, mass = scenario.rope, scenario.load.mass
        table = scenario.clutch.engagement_force
        return cls(
            motor_inertia=d.motor_inertia, output_inertia=d.output_inertia, stall_torque=d.stall_torque,
            no_load_speed=d.no_load_speed, capacity_per_newton=d.static_friction * d.clutch_constant,
            sliding_per_newton=d.kinetic_friction * d.clutch_constant, lever=d.rope_radius / d.ratio,
            ratio=d.ratio, mass=mass, gravity=scenario.gravity, stiffness=rope.stiffness,
            damping=2.0 * rope.damping_ratio * math.sqrt(rope.stiffness * mass),
            force_times=tuple(float(t) for t in table.times), forces=tuple(float(f) for f in table.forces),
            on_ground=scenario.ground is not None)


@dataclass
class Phase:
    start: float
    end: float
    z0: np.ndarray
    a: np.ndarray
    clutch: str
    taut: bool
    aloft: bool


@dataclass
class ExactRope:
    """The piecewise solution: its phases, its switches (time, kind) and the rope's peaks."""

    hoist: RopeHoist
    phases: list = field(default_factory=list)
    events: list = field(default_factory=list)
    peaks: list = field(default_factory=list)  # (time, force) of every maximum of the rope force while taut

    def state(self, t: float) -> tuple[np.ndarray, Phase]:
        """The state at t and the phase it belongs to (the later one at a switch)."""
        phase = next((p for p in reversed(self.phases) if p.start <= t), self.phases[0])
        return expm(phase.a * (t - phase.start)) @ phase.z0, phase

    def series(self, times) -> dict[str, np.ndarray]:
        """The run's columns at these times: speeds, the load's height and speed, the rope's stretch and force."""
        rows = []
        for t in np.asarray(times, dtype=float):
            z, phase = self.state(t)
            rows.append((z[WM], z[WP] / self.hoist.ratio, z[S], z[V], z[X],
                         float(self._force_row(phase.taut) @ z)))
        names = ("motor_speed", "drum_speed", "rope_stretch", "load_velocity", "load_position", "rope_force")
        return {name: np.asarray(values) for name, values in zip(names, zip(*rows))}

    @property
    def peak_rope_force(self) -> float:
        return max(force for _, force in self.peaks)

    def _force_row(self, taut: bool) -> np.ndarray:
        h, row = self.hoist, np.zeros(7)
        if taut:
            row[S] = h.stiffness
            row[WP] += h.damping * h.lever
            row[V] -= h.damping
        return row


def solve(hoist: RopeHoist, duration: float, initial: tuple) -> ExactRope:
    """The exact solution from (motor speed, pinion speed, stretch, load speed) at t = 0 to ``duration``."""
    out = ExactRope(hoist)
    z = np.array([*initial, 0.0, 0.0, 1.0], dtype=float)
    boundaries = sorted({0.0, duration, *(t for t in hoist.force_times if 0.0 < t < duration)})
    aloft = not hoist.on_ground
    taut, clutch = _rope_decision(out, z), None
    t = 0.0
    for end in boundaries[1:]:
        line = _segment_force(hoist, t, end)
        clutch = _clutch_decision(out, z, line, taut, aloft)
        aloft = aloft or (hoist.on_ground and _lifts(out, z, taut))
        while t < end:
            a = _matrix(hoist, line, clutch, taut, aloft)
            guards = _guards(out, a, line, clutch, taut, aloft)
            hit, kind, z_hit = _first_root(a, z, t, end, guards)
            out.phases.append(Phase(t, hit, z.copy(), a, clutch, taut, aloft))
            if taut:
                out.peaks += _peaks(out, a, z, t, hit)
            t, z = hit, z_hit
            if kind is None:
                break
            if kind == "slip":
                clutch = _clutch_decision(out, z, line, taut, aloft, met=True)
            elif kind in ("breakaway+", "breakaway-"):
                clutch = SLIP_FORWARD if kind == "breakaway+" else SLIP_BACKWARD
            elif kind == "lift_off":
                aloft = True
            elif kind == "touch_down":
                z[V] = 0.0  # a plastic impact
                aloft = _lifts(out, z, taut)
            elif kind in ("rope_slack", "rope_taut"):
                taut = kind == "rope_taut"
            out.events.append((t, {"slip": "lock" if clutch == LOCKED else "reversal",
                                   "breakaway+": "unlock", "breakaway-": "unlock"}.get(kind, kind)))
    out.phases.append(Phase(duration, duration, z.copy(), out.phases[-1].a, clutch, taut, aloft))
    return out


def _segment_force(hoist: RopeHoist, start: float, end: float) -> tuple[float, float]:
    """The engagement force over (start, end), a line: (its value at t = 0, its slope)."""
    times, forces = np.asarray(hoist.force_times), np.asarray(hoist.forces)
    after = np.nonzero(times <= start)[0]  # at a step, the value after it
    f0 = float(forces[after[-1]]) if after.size and times[after[-1]] == start else float(np.interp(start, times, forces))
    f1 = float(np.interp(end, times, forces))
    if (times == end).sum() > 1:  # a step at the end: the value before it
        f1 = float(forces[np.nonzero(times == end)[0][0]])
    slope = (f1 - f0) / (end - start)
    return f0 - slope * start, slope


def _matrix(h: RopeHoist, force_line, clutch: str, taut: bool, aloft: bool) -> np.ndarray:
    a = np.zeros((7, 7))
    rope = np.zeros(7)
    if taut:
        rope[S], rope[WP], rope[V] = h.stiffness, h.damping * h.lever, -h.damping
    motor = np.zeros(7)
    motor[ONE], motor[WM] = h.stall_torque, -h.stall_torque / h.no_load_speed
    sliding = np.zeros(7)
    sliding[ONE], sliding[T] = h.sliding_per_newton * force_line[0], h.sliding_per_newton * force_line[1]
    if clutch == LOCKED:
        a[WM] = a[WP] = (motor - h.lever * rope) / (h.motor_inertia + h.output_inertia)
    else:
        sigma = SIGN[clutch]
        a[WM] = (motor - sigma * sliding) / h.motor_inertia
        a[WP] = (sigma * sliding - h.lever * rope) / h.output_inertia
    a[S, WP], a[S, V] = h.lever, -1.0
    if aloft:
        a[V] = rope / h.mass
        a[V, ONE] -= h.gravity
        a[X, V] = 1.0
    a[T, ONE] = 1.0
    return a


def _clutch_torque_row(out: ExactRope, a_locked: np.ndarray) -> np.ndarray:
    """The torque a locked clutch carries, as a row on z: C(w) - J_a w'."""
    h = out.hoist
    motor = np.zeros(7)
    motor[ONE], motor[WM] = h.stall_torque, -h.stall_torque / h.no_load_speed
    return motor - h.motor_inertia * a_locked[WM]


def _capacity_row(h: RopeHoist, force_line) -> np.ndarray:
    row = np.zeros(7)
    row[ONE], row[T] = h.capacity_per_newton * force_line[0], h.capacity_per_newton * force_line[1]
    return row


def _guards(out: ExactRope, a, line, clutch, taut, aloft) -> dict:
    """Each switch's guard as a function of z, positive inside the phase, crossing zero at the switch."""
    h = out.hoist
    force = out._force_row(True)
    guards = {}
    if clutch == LOCKED:
        torque = _clutch_torque_row(out, a)
        capacity = _capacity_row(h, line)
        guards["breakaway+"] = lambda z: capacity @ z - torque @ z
        guards["breakaway-"] = lambda z: capacity @ z + torque @ z
    elif clutch != OPEN:
        sigma = SIGN[clutch]
        guards["slip"] = lambda z: sigma * (z[WM] - z[WP])
    if taut:
        guards["rope_slack"] = lambda z: min(h.stiffness * z[S], force @ z)
    else:
        guards["rope_taut"] = lambda z: -min(h.stiffness * z[S], force @ z)
    if h.on_ground and not aloft:
        guards["lift_off"] = lambda z: h.mass * h.gravity - (force @ z if taut else 0.0)
    if h.on_ground and aloft:
        guards["touch_down"] = lambda z: z[X]
    return guards


def _first_root(a, z0, t0, end, guards):
    """The earliest switch in (t0, end]: (its time, its kind, the state there), or (end, None, state)."""
    step = expm(a * SAMPLE)
    # a guard fires once it has been positive: one that starts at zero (it ended the last phase) waits
    armed = {name: g(z0) > 0.0 for name, g in guards.items()}
    t, z = t0, z0
    while t < end:
        whole = t + SAMPLE < end  # a whole sample: one product with its exponential; the last, its own
        t_next = t + SAMPLE if whole else end
        z_next = step @ z if whole else expm(a * (t_next - t0)) @ z0
        crossed = []
        for name, g in guards.items():
            value = g(z_next)
            if armed[name] and value <= 0.0:
                crossed.append(name)
            elif not armed[name] and value > 0.0:
                # armed within this sample: a root between its arming and here cannot be, it just rose
                armed[name] = True
        if crossed:
            best = None
            for name in crossed:
                g = guards[name]
                root = brentq(lambda s: g(expm(a * (s - t0)) @ z0), t, t_next, xtol=1e-15, rtol=8.9e-16,
                              maxiter=200)
                if best is None or root < best[0]:
                    best = (root, name)
            root, name = best
            return root, name, expm(a * (root - t0)) @ z0
        t, z = t_next, z_next
    return end, None, expm(a * (end - t0)) @ z0


def _peaks(out: ExactRope, a, z0, t0, t1) -> list:
    """Maxima of the rope force over a taut phase: roots of its rate where it falls, and the ends."""
    force = out._force_row(True)
    rate = force @ a

    def at(t):
        return expm(a * (t - t0)) @ z0

    found = [(t0, float(force @ z0)), (t1, float(force @ at(t1)))]
    times = np.arange(t0, t1, SAMPLE)
    values = [float(rate @ at(t)) for t in times] + [float(rate @ at(t1))]
    points = list(times) + [t1]
    for (ta, va), (tb, vb) in zip(zip(points, values), zip(points[1:], values[1:])):
        if va > 0.0 >= vb:
            root = brentq(lambda s: float(rate @ at(s)), ta, tb, xtol=1e-15, rtol=8.9e-16)
            found.append((root, float(force @ at(root))))
    return found


def _rope_decision(out: ExactRope, z) -> bool:
    """Taut where stretched and pulling; at exactly zero stretch, where the stretch's first nonzero
    derivative (in the taut law) is positive."""
    h = out.hoist
    if z[S] != 0.0:
        return z[S] > 0.0 and float(out._force_row(True) @ z) > 0.0
    a = _matrix(h, (h.forces[0], 0.0), LOCKED if z[WM] == z[WP] else SLIP_FORWARD, True, not h.on_ground)
    power = z.copy()
    for _ in range(4):
        power = a @ power
        if abs(power[S]) > 1e-300:
            return power[S] > 0.0
    return False


def _lifts(out: ExactRope, z, taut: bool) -> bool:
    h = out.hoist
    return taut and float(out._force_row(True) @ z) > h.mass * h.gravity


def _clutch_decision(out: ExactRope, z, line, taut, aloft, met: bool = False) -> str:
    """The clutch's mode: open without force; slipping the way its sides part; where they move
    together (``met``: they just met), locked if the torque a locked clutch carries fits its capacity,
    else slipping the way that torque pushes."""
    h = out.hoist
    force = line[0] + line[1] * z[T]
    if force <= 0.0:
        return OPEN
    if not met and abs(z[WM] - z[WP]) > 1e-12 * max(1.0, abs(z[WM])):
        return SLIP_FORWARD if z[WM] > z[WP] else SLIP_BACKWARD
    a = _matrix(h, line, LOCKED, taut, aloft)
    torque = float(_clutch_torque_row(out, a) @ z)
    if abs(torque) <= h.capacity_per_newton * force:
        return LOCKED
    return SLIP_FORWARD if torque > 0 else SLIP_BACKWARD

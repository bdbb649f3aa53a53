"""Modelica's CoupledClutches integrated independently with scipy, phase by phase, against hoistsim.

The machine is read from ``scenarios/coupled_clutches.yaml`` with plain YAML (ruamel.yaml's safe loader;
nothing of hoistsim's but ``load_scenario``/``simulate`` is used, and only to run hoistsim for the
comparison).  Within a phase the set of stuck clutches is fixed: shafts joined by stuck clutches turn as
one inertia, a slipping clutch passes kinetic * force * radius against its slip, an open one (force <= 0)
nothing.  ``solve_ivp`` (DOP853, rtol = atol = 1e-12) integrates each phase and its events end it:

- a slipping clutch's slip through zero;
- a stuck clutch's held torque (from the reduced equations of its stuck group) reaching static capacity;
- a force through zero (open / close);
- a force table's breakpoints (the steps at 0.4 s and 0.9 s), where the phase ends exactly.

At each switch the new set is chosen by an exhaustive check: every clutch at zero slip (stuck before, or
the one that just reached zero slip) tries stuck, slipping + and slipping -; a combination is consistent
when every stuck clutch's held torque is within its static capacity and every clutch slipping at zero
slip accelerates its slip the way it slips; the consistent one with the most clutches stuck is taken (a
clutch whose held torque just reached capacity may not stay stuck).  Then every hoistsim switch (time,
kind, clutch, mode after) and the four shaft speeds at every output row are compared, the middle phases
(0.4 s to 1.25 s, where clutches slip and lock in turn) on their own, and every clutch's torque between
switches.

What the comparison found: switches within 5e-11 s; speeds within 2.5e-9 rad/s to 1.25 s.  The largest
difference is where clutch 1 opens (1.2506 s): hoistsim's J2..J4 step up 2.7e-9 rad/s there and J1 down
8.1e-9 (momentum kept), beside the closed form of that last phase (J2..J4 together gain the integral of
10 sin(0.4 pi t + 1.57) / 3 from any row of it to the opening), so J1 ends 9.9e-9 off, near SPEED_TOL.
"""

from __future__ import annotations

import itertools
import math
import time

import numpy as np
import pytest
from helpers import SCENARIOS
from ruamel.yaml import YAML
from scipy.integrate import solve_ivp

SCENARIO = SCENARIOS / "coupled_clutches.yaml"
RTOL = ATOL = 1e-12
TIME_TOL = 1e-9  # s: every switch (reached: 4.7e-11, clutch 1's first lock)
SPEED_TOL = 1e-8  # rad/s: every shaft at every output row (reached: 9.9e-9, J1 after clutch 1 opens)
MIDDLE_TOL = 5e-9  # rad/s: 0.4 s to 1.25 s, where the clutches slip and lock in turn (reached: 2.5e-9)
TORQUE_TOL = 1e-9  # N*m: every clutch's torque at every row but the switches' own (reached: 4.4e-15)


# --------------------------------------------------------------------------------------------- the machine
def _quantity(value, unit: str) -> float:
    if isinstance(value, (int, float)):
        return float(value)
    number, _, given = str(value).strip().partition(" ")
    assert given.replace(" ", "") == unit, (value, unit)
    return float(number)


class Signal:
    """A time signal as the scenario writes it: a constant, a table (a repeated time is a step; linear in
    between, held after the ends) or an offset plus sum(amplitude sin(2 pi f t + phase))."""

    def __init__(self, spec, unit: str):
        self.table = None
        self.harmonics = []
        self.offset = 0.0
        if isinstance(spec, list):
            self.table = [(_quantity(t, "s"), _quantity(v, unit)) for t, v in spec]
        elif isinstance(spec, dict):
            assert set(spec) <= {"offset", "harmonics"}, spec
            self.offset = _quantity(spec.get("offset", 0.0), unit)
            for h in spec.get("harmonics", []):
                assert set(h) <= {"amplitude", "frequency", "phase"}, h
                self.harmonics.append((_quantity(h["amplitude"], unit), _quantity(h["frequency"], "Hz"),
                                       _quantity(h.get("phase", 0.0), "rad")))
        else:
            self.offset = _quantity(spec, unit)

    @property
    def breakpoints(self) -> list[float]:
        return sorted({t for t, _ in self.table}) if self.table else []

    @property
    def continuous(self) -> bool:  # may cross zero between breakpoints
        return bool(self.harmonics)

    def __call__(self, t: float) -> float:
        """The value at t; at a step, the value just after it."""
        if self.table is not None:
            rows = self.table
            if t < rows[0][0]:
                return rows[0][1]
            for (t0, v0), (t1, v1) in zip(rows, rows[1:]):
                if t0 <= t < t1:
                    return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
            return rows[-1][1]
        return self.offset + sum(a * math.sin(2 * math.pi * f * t + p) for a, f, p in self.harmonics)


class Machine:
    def __init__(self, path):
        scene = YAML(typ="safe").load(path.read_text(encoding="utf-8"))
        train = scene["drivetrain"]
        self.shafts = list(train["shafts"])
        self.inertia = np.array([_quantity(s["inertia"], "kg*m^2") for s in train["shafts"].values()])
        self.speed0 = np.array([_quantity(s.get("speed", 0.0), "rad/s") for s in train["shafts"].values()])
        self.torques = [(self.shafts.index(x["shaft"]), Signal(x["torque"], "N*m")) for x in train["torques"]]
        self.clutches = list(train["clutches"])
        self.ends, self.static, self.kinetic, self.force = [], [], [], []
        for c in train["clutches"].values():
            assert set(c) <= {"between", "static_friction", "kinetic_friction", "effective_radius", "surfaces",
                              "force"}, c
            a, b = c["between"]
            assert a in self.shafts and b in self.shafts, "a brake to ground is not drawn here"
            self.ends.append((self.shafts.index(a), self.shafts.index(b)))
            lever = _quantity(c["effective_radius"], "m") * c.get("surfaces", 1)
            self.static.append(c["static_friction"] * lever)  # torque per newton of force
            self.kinetic.append(c["kinetic_friction"] * lever)
            self.force.append(Signal(c["force"], "N"))
        sim = scene["simulation"]
        self.duration = _quantity(sim["duration"], "s")
        self.n = len(self.shafts)
        # incidence: clutch c's torque tau (passed from its first shaft to its second) acts -tau on a, +tau on b
        self.incidence = np.zeros((self.n, len(self.clutches)))
        for c, (a, b) in enumerate(self.ends):
            self.incidence[a, c], self.incidence[b, c] = -1.0, 1.0

    def external(self, t):
        torque = np.zeros(self.n)
        for shaft, signal in self.torques:
            torque[shaft] += signal(t)
        return torque

    def slip(self, y, c):
        a, b = self.ends[c]
        return y[a] - y[b]


# --------------------------------------------------------------------------------- one phase's equations
# A mode per clutch: "open", "stuck", +1 or -1 (slipping that way).
def _groups(machine, modes):
    parent = list(range(machine.n))

    def root(i):
        while parent[i] != i:
            i = parent[i]
        return i

    for c, m in enumerate(modes):
        if m == "stuck":
            a, b = machine.ends[c]
            parent[root(a)] = root(b)
    return np.array([root(i) for i in range(machine.n)])


class Phase:
    """The reduced equations of one set of modes: group accelerations and the stuck clutches' torques."""

    def __init__(self, machine, modes):
        self.machine, self.modes = machine, tuple(modes)
        self.group = _groups(machine, modes)
        self.members = {g: np.flatnonzero(self.group == g) for g in np.unique(self.group)}
        self.stuck = [c for c, m in enumerate(modes) if m == "stuck"]
        self.sliding = [c for c, m in enumerate(modes) if m in (1, -1)]
        # held torques solve incidence[:, stuck] tau = J alpha - known, one answer per tree of stuck clutches
        self.pinv = np.linalg.pinv(machine.incidence[:, self.stuck]) if self.stuck else None

    def known(self, t):
        """Every torque on every shaft but the stuck clutches' (external and sliding)."""
        m = self.machine
        torque = m.external(t)
        for c in self.sliding:
            a, b = m.ends[c]
            tau = self.modes[c] * m.kinetic[c] * m.force[c](t)
            torque[a] -= tau
            torque[b] += tau
        return torque

    def acceleration(self, t, known=None):
        known = self.known(t) if known is None else known
        J = self.machine.inertia
        alpha = np.empty(self.machine.n)
        for members in self.members.values():
            alpha[members] = known[members].sum() / J[members].sum()
        return alpha

    def held(self, t):
        """The stuck clutches' torques (in the order of self.stuck)."""
        if not self.stuck:
            return np.zeros(0)
        known = self.known(t)
        alpha = self.acceleration(t, known)
        return self.pinv @ (self.machine.inertia * alpha - known)

    def rhs(self, t, y):
        return self.acceleration(t)


def _consistent(machine, modes, t, zero_slip):
    """Whether modes hold at t: stuck torques within capacity, slips at zero slip accelerating their way."""
    phase = Phase(machine, modes)
    for c, tau in zip(phase.stuck, phase.held(t)):
        if abs(tau) > machine.static[c] * machine.force[c](t) * (1 + 1e-12) + 1e-12:
            return False
    alpha = phase.acceleration(t)
    for c in zero_slip:
        if modes[c] in (1, -1):
            a, b = machine.ends[c]
            if modes[c] * (alpha[a] - alpha[b]) < -1e-12:
                return False
    return True


def _decide(machine, t, y, closed, candidates, broke_loose=None):
    """The modes after a switch at t: each closed clutch at zero slip (candidates) tries stuck, + and -, and
    the consistent combination with the most clutches stuck wins (one whose held torque just reached its
    capacity, broke_loose, may not stay stuck).  The other closed ones slip the way their slip says."""
    base = []
    for c in range(len(machine.clutches)):
        if not closed[c]:
            base.append("open")
        elif c in candidates:
            base.append(None)
        else:
            s = machine.slip(y, c)
            assert s != 0.0, (t, c)
            base.append(1 if s > 0 else -1)
    free = [c for c in range(len(base)) if base[c] is None]
    found = []
    for choice in itertools.product(("stuck", 1, -1), repeat=len(free)):
        modes = list(base)
        for c, m in zip(free, choice):
            modes[c] = m
        if broke_loose is not None and modes[broke_loose] == "stuck":
            continue
        if _consistent(machine, modes, t, free):
            found.append(tuple(modes))
    assert found, (t, base)
    most = max(m.count("stuck") for m in found)
    best = [m for m in found if m.count("stuck") == most]
    assert len(best) == 1, (t, best)  # friction leaves one answer
    return best[0]


# ------------------------------------------------------------------------------------------ the integration
def _event(fun, direction):
    fun.terminal, fun.direction = True, direction
    return fun


def integrate(machine):
    """Phase by phase: [(t0, t1, dense solution, modes)] and the switches [(time, kind, clutch, mode after)]."""
    count = len(machine.clutches)
    breaks = sorted({b for f in machine.force for b in f.breakpoints if 0.0 < b < machine.duration})
    t, y = 0.0, machine.speed0.copy()
    closed = [machine.force[c](t) > 0.0 for c in range(count)]
    modes = _decide(machine, t, y, closed, [c for c in range(count) if closed[c] and machine.slip(y, c) == 0.0])
    segments, switches = [], []
    while True:
        phase = Phase(machine, modes)
        end = min([b for b in breaks if b > t] + [machine.duration])
        events, meaning = [], []
        for c, m in enumerate(modes):
            if m in (1, -1):  # slip through zero
                events.append(_event(lambda s, x, c=c: machine.slip(x, c), -m))
                meaning.append(("slip", c))
            if m == "stuck":  # held torque up to capacity, either way
                k = phase.stuck.index(c)
                for sign in (1, -1):
                    events.append(_event(lambda s, x, c=c, k=k, sign=sign:
                                         machine.static[c] * machine.force[c](s) - sign * phase.held(s)[k], -1))
                    meaning.append(("capacity", c))
            if machine.force[c].continuous:  # force through zero, the way that opens or closes it
                events.append(_event(lambda s, x, c=c: machine.force[c](s), -1 if closed[c] else 1))
                meaning.append(("force", c))
        sol = solve_ivp(phase.rhs, (t, end), y, method="DOP853", rtol=RTOL, atol=ATOL, dense_output=True,
                        events=events)
        assert sol.success, sol.message
        fired = [i for i, te in enumerate(sol.t_events) if te.size]
        before = modes
        stuck = [k for k, m in enumerate(before) if m == "stuck"]  # every stuck clutch is asked again
        if not fired:  # to a breakpoint of a table (or the end)
            t1, y1 = end, sol.y[:, -1].copy()
            segments.append((t, t1, sol.sol, before))
            if t1 >= machine.duration:
                return segments, switches
            closed = [machine.force[c](t1) > 0.0 if not machine.force[c].continuous else closed[c]
                      for c in range(count)]
            modes = _decide(machine, t1, y1, closed, stuck)
            c = None
        else:
            assert len(fired) == 1, [(meaning[i], sol.t_events[i]) for i in fired]
            i = fired[0]
            t1, y1 = float(sol.t_events[i][0]), sol.y_events[i][0].copy()
            segments.append((t, t1, sol.sol, before))
            what, c = meaning[i]
            if what == "slip":
                a, b = machine.ends[c]
                J = machine.inertia
                shared = (J[a] * y1[a] + J[b] * y1[b]) / (J[a] + J[b])
                for g in (phase.group[a], phase.group[b]):  # slip exactly zero: both sides take the shared speed
                    y1[phase.members[g]] = shared
                modes = _decide(machine, t1, y1, closed, sorted({c, *stuck}))
                switches.append((t1, "lock" if modes[c] == "stuck" else "reverse", c, modes[c]))
            elif what == "capacity":
                modes = _decide(machine, t1, y1, closed, stuck, broke_loose=c)
                switches.append((t1, "unlock", c, modes[c]))
            else:  # force through zero
                closed = list(closed)
                closed[c] = not closed[c]
                zero = closed[c] and machine.slip(y1, c) == 0.0
                modes = _decide(machine, t1, y1, closed, sorted({*stuck, *([c] if zero else [])}))
                switches.append((t1, "engage" if closed[c] else "disengage", c, modes[c]))
        for k, (m0, m1) in enumerate(zip(before, modes)):  # every other clutch the new set changes
            if k == c or m0 == m1:
                continue
            kind = ("engage" if m0 == "open" else "disengage" if m1 == "open" else "lock" if m1 == "stuck"
                    else "unlock" if m0 == "stuck" else "reverse")
            switches.append((t1, kind, k, m1))
        t, y = t1, y1


def evaluate(segments, times):
    out = np.empty((len(times), len(segments[0][2](segments[0][0]))))
    starts = np.array([s[0] for s in segments])
    for j, t in enumerate(times):
        k = max(0, int(np.searchsorted(starts, t, side="right")) - 1)
        t0, t1, sol, _ = segments[k]
        assert t0 <= t <= t1 + 1e-15, (t, t0, t1)
        out[j] = sol(min(t, t1))
    return out


# --------------------------------------------------------------------------------------------------- tests
@pytest.fixture(scope="module")
def scipy_answer():
    machine = Machine(SCENARIO)
    start = time.perf_counter()
    segments, switches = integrate(machine)
    return machine, segments, switches, time.perf_counter() - start


@pytest.fixture(scope="module")
def hoistsim_run():
    from hoistsim import load_scenario, simulate

    return simulate(load_scenario(SCENARIO))


def test_scipy_phases_switch_as_the_modelica_example(scipy_answer):
    machine, _, switches, seconds = scipy_answer
    got = [(kind, machine.clutches[c]) for _, kind, c, _ in switches]
    assert got == [("engage", "clutch2"), ("lock", "clutch2"), ("lock", "clutch1"), ("unlock", "clutch1"),
                   ("engage", "clutch3"), ("lock", "clutch1"), ("unlock", "clutch1"), ("lock", "clutch3"),
                   ("disengage", "clutch1")]
    times = [t for t, *_ in switches]
    assert times[0] == 0.4 and times[4] == 0.9
    assert times[-1] == pytest.approx((math.pi - 1.57) / (0.4 * math.pi), abs=1e-12)
    assert seconds < 60


@pytest.mark.slow  # hoistsim's compile of this scene: ~15 s
def test_hoistsim_switches_where_scipy_does(scipy_answer, hoistsim_run):
    machine, _, switches, _ = scipy_answer
    ev = hoistsim_run.events
    theirs = [(float(t), str(k), str(e), str(m)) for t, k, e, m in zip(ev["time"], ev["kind"], ev["element"],
                                                                      ev["mode_after"])]
    ours = [(t, kind, machine.clutches[c], m) for t, kind, c, m in switches]
    assert [x[1:3] for x in theirs] == [x[1:3] for x in ours]
    names = {"stuck": "locked", 1: "slipping+", -1: "slipping-"}
    for (t_h, kind, element, mode_h), (t_s, _, _, mode_s) in zip(theirs, ours):
        if kind != "disengage":  # hoistsim writes the last sliding direction there
            assert mode_h == names[mode_s], (kind, element, mode_h, mode_s)
        assert abs(t_h - t_s) < TIME_TOL, (kind, element, t_h, t_s, t_h - t_s)


@pytest.mark.slow  # hoistsim's compile of this scene: ~15 s
def test_hoistsim_speeds_as_scipy_at_every_row(scipy_answer, hoistsim_run):
    machine, segments, _, _ = scipy_answer
    run = hoistsim_run
    ours = evaluate(segments, run.time)
    middle = (run.time >= 0.4) & (run.time <= 1.25)
    for k, shaft in enumerate(machine.shafts):
        theirs = np.asarray(run[f"{shaft}_speed"])
        diff = np.abs(theirs - ours[:, k])
        worst = int(np.argmax(diff))
        assert diff.max() < SPEED_TOL, (shaft, float(run.time[worst]), float(diff.max()))
        assert diff[middle].max() < MIDDLE_TOL, (shaft, float(diff[middle].max()))


@pytest.mark.slow  # hoistsim's compile of this scene: ~15 s
def test_hoistsim_clutch_torques_as_scipy_between_switches(scipy_answer, hoistsim_run):
    """Each row's set of modes the same: the sliding torques and the stuck ones' held torques (a function of
    time alone here) at every row but the switches' own, where the torque jumps."""
    machine, segments, _, _ = scipy_answer
    run = hoistsim_run
    switches = set(np.asarray(run.events["time"], dtype=float).tolist())
    starts = np.array([s[0] for s in segments])
    for c, name in enumerate(machine.clutches):
        theirs = np.asarray(run[f"{name}_torque"])
        worst = 0.0
        for j, t in enumerate(np.asarray(run.time, dtype=float)):
            if t in switches:
                continue
            phase = Phase(machine, segments[int(np.searchsorted(starts, t, side="right")) - 1][3])
            mode = phase.modes[c]
            ours = (0.0 if mode == "open" else phase.held(t)[phase.stuck.index(c)] if mode == "stuck"
                    else mode * machine.kinetic[c] * machine.force[c](t))
            worst = max(worst, abs(theirs[j] - ours))
        assert worst < TORQUE_TOL, (name, worst)

"""A buffer under the hoisted load (the hoist's ``buffer:``, a drawn load's ``drivetrain.load.buffer``).

- scenarios/load_onto_a_buffer.yaml: the load runs down onto it, the rope going slack; the ledger closes with the
  buffer's strain energy and its damper's heat, and its summaries are those of its event rows.
- Closed form: a load falling on a slack rope meets the buffer at the free fall's speed; on it, while the damping's
  push is limited to the spring's, M d'' = M g - 2 k d; then M d'' + c d' + k d = M g until the push k d + c d'
  falls to zero (the separation): its contact, its phases, its force at every row, its peak, and EN 13001-2's
  design force for the impact, phi7 = 1.25 times M g + sqrt((M g)^2 + k M v^2).
- New values of its keys compile nothing.
- A drawn drivetrain's load is the mass ``load`` a line's parts join: a drawn gap under it is the load's own buffer
  (the same trajectory and force), and a force on it that bears its weight lets its stretched rope throw it up as
  the closed form says.
- Bad input: a buffer on a rigid rope, with the ground under the load, a clearance not above zero, on a drawn load
  without a rope, a mass named ``load`` beside a drawn load: one line naming the key, nothing written.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import SCENARIOS, refused_in_one_line

from hoistsim import load_scenario, simulate

SCENE = SCENARIOS / "load_onto_a_buffer.yaml"
G = 9.81
# the shipped machine with its rope slack at the start (1 m paid out beyond taut), the buffer 0.3 m down and
# lightly damped, no brake applied before the end: the load falls freely onto the buffer and bounces off it
FALLING = ["rope.initial_slack=1 m", "buffer.clearance=0.3 m", "buffer.damping=2 kN*s/m", "brake.apply_time=0.5 s",
           "simulation.duration=0.5 s", "simulation.rtol=1e-11", "simulation.atol=1e-13"]


@pytest.fixture(scope="module")
def shipped():
    return simulate(load_scenario(SCENE))


@pytest.fixture(scope="module")
def falling():
    return simulate(load_scenario(SCENE, overrides=FALLING))


def test_the_load_runs_down_onto_its_buffer_and_the_ledger_closes(shipped):
    """The shipped run: the load meets the buffer at 0.423 s going 1.89 m/s, the rope goes slack after, the buffer
    peaks at 19.7 kN pressed in 92.8 mm; the load leaves it, lands again and rests on it.  The summaries are the
    rows': the speed at the contact row, the largest push and compression of any row."""
    run = shipped
    kinds, times = list(run.instants["kind"]), run.instants["time"]
    assert kinds.count("contact") == 2 and kinds.count("separation") == 1
    contact = times[kinds.index("contact")]
    assert contact == pytest.approx(0.4228, abs=1e-4)
    assert times[kinds.index("rope_slack")] > contact
    at_contact = np.flatnonzero(run.time == contact)[0]
    assert run.summary["buffer_impact_speed"] == pytest.approx(-run["load_velocity"][at_contact], rel=1e-12)
    assert run.summary["peak_buffer_force"] == pytest.approx(run["buffer_force"].max(), rel=1e-12)
    assert run.summary["peak_buffer_force"] == pytest.approx(19733.2, rel=1e-4)
    assert run.summary["peak_buffer_compression"] == pytest.approx(run["buffer_compression"].max(), rel=1e-12)
    assert (run["buffer_force"] >= 0.0).all() and (run["buffer_compression"] >= 0.0).all()
    assert ((run["buffer_contact"] == 1) == (run["buffer_force"] > 0.0)).mean() > 0.999  # rows at the contact: 0
    # resting on the buffer at the end, the rope slack: its weight on the buffer's spring
    assert run["buffer_force"][-1] == pytest.approx(500.0 * G, rel=2e-2)  # still ringing down: 4854 N
    assert run["rope_force"][-1] == 0.0
    assert run.ledger["buffer_damping_loss"][-1] > 0.0
    assert run.summary["energy_relative_residual"] < 1e-6


def test_a_load_falling_on_a_slack_rope_meets_its_buffer_as_the_closed_form(falling):
    """500 kg going down at 0.5 m/s, 1 m of slack rope, the buffer (2e5 N/m, 2e3 N*s/m) 0.3 m down: free fall until
    x = 0.3 m, contact speed sqrt(0.5^2 + 2 g 0.3); then the two phases of the buffer's law (see the module),
    the rope slack throughout (the drum pays out 0.5 m/s, less than the load's fall took up)."""
    from scipy.optimize import brentq, minimize_scalar

    run = falling
    m, k, d, h, v = 500.0, 2e5, 2e3, 0.3, 0.5
    t_contact = (-v + math.sqrt(v * v + 2 * G * h)) / G
    v0 = v + G * t_contact
    w1 = math.sqrt(2 * k / m)

    def first(tau):  # (d, d') while the damping's push is limited to the spring's
        a = m * G / (2 * k)
        return (a * (1 - math.cos(w1 * tau)) + v0 / w1 * math.sin(w1 * tau),
                a * w1 * math.sin(w1 * tau) + v0 * math.cos(w1 * tau))

    t1 = brentq(lambda tau: d * first(tau)[1] - k * first(tau)[0], 1e-9, math.pi / (2 * w1))
    x1, v1 = first(t1)
    zeta, w0 = d / (2 * math.sqrt(k * m)), math.sqrt(k / m)
    wd, rest = w0 * math.sqrt(1 - zeta**2), m * G / k

    def later(tau):  # (d, d') after t1: a damped oscillator about its rest on the buffer
        decay, a = math.exp(-zeta * w0 * tau), x1 - rest
        b = (v1 + zeta * w0 * a) / wd
        return (rest + decay * (a * math.cos(wd * tau) + b * math.sin(wd * tau)),
                decay * ((b * wd - zeta * w0 * a) * math.cos(wd * tau) - (a * wd + zeta * w0 * b) * math.sin(wd * tau)))

    def push(tau):
        x, dx = first(tau) if tau < t1 else later(tau - t1)
        return k * x + min(k * x, d * dx)

    apart = brentq(lambda tau: push(t1 + tau), math.pi / (2 * wd), 1.5 * math.pi / wd)
    peak = -minimize_scalar(lambda tau: -push(t1 + tau), bounds=(0.0, apart), method="bounded",
                            options={"xatol": 1e-12}).fun
    kinds, times = list(run.instants["kind"]), run.instants["time"]
    contact, separation = times[kinds.index("contact")], times[kinds.index("separation")]
    assert contact == pytest.approx(t_contact, abs=1e-9)
    assert run.summary["buffer_impact_speed"] == pytest.approx(v0, rel=1e-9)
    assert times[kinds.index("gap_damping_limit")] - contact == pytest.approx(t1, abs=1e-9)
    assert separation - contact == pytest.approx(t1 + apart, abs=1e-9)
    rows = (run.time > contact) & (run.time < separation)
    expected = [push(tau) for tau in run.time[rows] - contact]
    np.testing.assert_allclose(run["buffer_force"][rows], expected, rtol=0, atol=1e-7 * peak)
    assert (run["rope_force"][rows] == 0.0).all()
    assert run.summary["peak_buffer_force"] == pytest.approx(peak, rel=1e-8)
    weight = m * G
    standard = 1.25 * (weight + math.sqrt(weight**2 + k * m * v0**2))
    assert run.summary["buffer_force_standard"] == pytest.approx(standard, rel=1e-9)
    assert run.summary["energy_relative_residual"] < 1e-9


def test_new_values_of_the_buffers_keys_compile_nothing(falling):
    from hoistsim.machine.core import loop

    traced = loop.trace_count
    changed = simulate(load_scenario(SCENE, overrides=[*FALLING, "buffer.clearance=0.35 m",
                                                       "buffer.stiffness=3e5 N/m", "buffer.damping=1 kN*s/m"]))
    assert loop.trace_count == traced
    assert changed.summary["peak_buffer_force"] != pytest.approx(falling.summary["peak_buffer_force"])


def _drop(key):
    def change(data):
        del data[key]
    return change


@pytest.mark.parametrize("change, key, says", [
    (_drop("rope"), "buffer", "needs an elastic rope"),
    (lambda data: data.update(ground={}), "buffer", "cannot be given with ground"),
    (lambda data: data["buffer"].update(clearance="0 m"), "buffer.clearance", "must be positive"),
    (lambda data: data["buffer"].update(stiffness="-1 N/m"), "buffer.stiffness", "must be positive"),
])
def test_a_buffer_the_load_cannot_meet_is_refused_in_one_line(change, key, says, tmp_path):
    refused_in_one_line(SCENE, change, key, says, tmp_path)


def test_a_drawn_loads_buffer_needs_its_rope(tmp_path):
    def drawn(data):
        data.clear()
        data.update({"name": "drawn", "drivetrain": {
            "shafts": {"drum": {"inertia": "10 kg*m^2"}},
            "load": {"shaft": "drum", "rope_radius": "0.2 m", "mass": "500 kg",
                     "buffer": {"clearance": "0.5 m", "stiffness": "2e5 N/m"}}},
            "simulation": {"duration": "1 s", "output_interval": "1 ms"}})
    refused_in_one_line(SCENE, drawn, "drivetrain.load.buffer", "needs an elastic rope", tmp_path)


def _drawn(buffer_as: str, **more):
    """A drum paying out 0.5 m/s of rope to 500 kg on an elastic rope, a buffer 0.5 m down: the load's own
    ``buffer`` key, or a drawn gap between the ground and the load (the mass ``load``)."""
    from hoistsim import scenario_from_dict

    buffer = {"clearance": "0.5 m", "stiffness": "200 kN/m", "damping": "4 kN*s/m"}
    load = {"shaft": "drum", "rope_radius": "20 cm", "mass": "500 kg",
            "rope": {"stiffness": "475 kN/m", "damping_ratio": 0.02}}
    drivetrain = {"shafts": {"drum": {"inertia": "20 kg*m^2", "speed": "-2.5 rad/s"}}, "load": load, **more}
    if buffer_as == "key":
        load["buffer"] = buffer
    else:
        drivetrain["springs"] = {"buffer": {"between": ["ground", "load"], "stiffness": "200 kN/m",
                                            "damping": "4 kN*s/m", "unstretched_length": "-0.5 m", "gap": True}}
    return scenario_from_dict({"name": "drawn", "drivetrain": drivetrain, "simulation": {
        "duration": "1.2 s", "output_interval": "1 ms", "rtol": 1e-10, "atol": 1e-12}})


def _on_the_grid(run, column):
    """A column at the output grid's rows (every ms), without the rows of events the runs differ in."""
    steps = run.time / 1e-3
    rows = np.abs(steps - np.round(steps)) < 1e-6
    _, first = np.unique(np.round(steps[rows]), return_index=True)
    return run[column][rows][first]


def test_the_load_is_a_mass_on_the_line_that_a_drawn_part_joins():
    """A drawn drivetrain's load is the mass ``load``: a drawn gap between the ground and it is the load's own
    buffer (the same law, the same contact and force at every row), and a constant force on it is a lighter
    weight (g less F / M: the same height at every row)."""
    keyed, drawn = simulate(_drawn("key")), simulate(_drawn("spring"))
    contact = drawn.instants["time"][list(drawn.instants["kind"]).index("contact")]
    assert contact == pytest.approx(keyed.instants["time"][list(keyed.instants["kind"]).index("contact")], abs=1e-9)
    np.testing.assert_allclose(_on_the_grid(drawn, "load_position"), _on_the_grid(keyed, "load_position"), rtol=0,
                               atol=1e-8)
    np.testing.assert_allclose(-_on_the_grid(drawn, "buffer_force"), _on_the_grid(keyed, "buffer_force"), rtol=0,
                               atol=1e-6 * keyed["buffer_force"].max())
    assert drawn.summary["energy_relative_residual"] < 1e-8


def test_a_force_on_the_drawn_load_that_bears_its_weight_lets_the_rope_throw_it_up():
    """A force M g up on the load (the mass ``load``) hanging still on its stretched rope (k, undamped), the drum
    held: the load's weight is borne, the rope's stretch M g / k throws it up, x = (M g / k)(1 - cos w t),
    w = sqrt(k / M), until the rope is unstretched at w t = pi / 2 (it goes slack there); then it flies on at
    (M g / k) w.  Its height at every row."""
    from hoistsim import scenario_from_dict

    m, k, g = 500.0, 475e3, 9.81
    run = simulate(scenario_from_dict({"name": "thrown", "drivetrain": {
        "shafts": {"drum": {"inertia": "20 kg*m^2"}},
        "load": {"shaft": "drum", "rope_radius": "20 cm", "mass": f"{m} kg", "rope": {"stiffness": f"{k} N/m"}},
        "brakes": {"held": {"shaft": "drum", "release_time": "1 s"}},  # holding the drum throughout
        "forces": [{"mass": "load", "force": [["0 s", f"{m * g} N"], ["0.1 s", f"{m * g} N"]]}]},
        "simulation": {"duration": "0.1 s", "output_interval": "0.5 ms", "rtol": 1e-11, "atol": 1e-13}}))
    stretch, w = m * g / k, math.sqrt(k / m)
    slack = math.pi / (2 * w)
    expected = np.where(run.time < slack, stretch * (1 - np.cos(w * run.time)),
                        stretch + stretch * w * (run.time - slack))
    np.testing.assert_allclose(run["load_position"], expected, rtol=0, atol=1e-9 * expected.max())
    kinds = list(run.instants["kind"])
    assert run.instants["time"][kinds.index("rope_slack")] == pytest.approx(slack, abs=1e-9)
    assert run.summary["energy_relative_residual"] < 1e-9


def test_a_mass_named_load_beside_the_drawn_load_is_refused(tmp_path):
    def named(data):
        data.clear()
        data.update({"name": "drawn", "drivetrain": {
            "shafts": {"drum": {"inertia": "10 kg*m^2"}}, "masses": {"load": {"mass": "1 kg"}},
            "load": {"shaft": "drum", "rope_radius": "0.2 m", "mass": "500 kg"}},
            "simulation": {"duration": "1 s", "output_interval": "1 ms"}})
    refused_in_one_line(SCENE, named, "drivetrain.masses.load", "is the name of the drivetrain's load", tmp_path)

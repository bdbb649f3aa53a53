"""The flywheel that keeps a machine's degree of irregularity at a target: Tredgold's, and the simulation's.

Tredgold: I_required = Delta E_max / (w_m^2 delta), the flywheel what it adds
to the machine's own constant inertia (both at the motor shaft; a flywheel on
the drum is worth r^2 times its inertia there, r = w_drum / w_motor).

The simulation: the flywheel whose run meets delta exactly, a root of
delta(I) - target bracketed by candidate flywheels, each batch of them one
vectorised call of the compiled loop.  delta falls as 1/(I_own + I), so 1/delta
is nearly linear in I: interpolating it between the two candidates that
bracket the target is already close; a second batch, spread a few parts in a
thousand about that answer, brackets it tightly for the final interpolation,
and a third run checks it.  Three calls of 8 runs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..errors import ScenarioError
from ..running import simulation
from ..running.sweeps import simulate_many
from ..scenario.schema import FlywheelSpec, InitialSpec

# Candidates per vectorised call.  The first call spreads them over SPREAD times Tredgold's flywheel
# (the wider WIDE_SPREAD if the target is not between them); the second spreads them REFINE either
# side of the first interpolated answer; the third checks the answer.
CANDIDATES = 8
SPREAD, WIDE_SPREAD, REFINE = (0.6, 1.6), (0.2, 5.0), 2e-3


@dataclass
class Sizing:
    """What the flywheel command answers (SI units), and the candidates it simulated."""

    shaft: str
    irregularity: float  # the target
    mean_speed: float  # rad/s at the motor shaft, from the run of the machine as given
    energy_fluctuation: float  # J, Tredgold's Delta E_max
    machine_inertia: float  # kg*m^2 at the motor shaft: the machine's own constant inertia
    required_inertia_tredgold: float  # kg*m^2 at the motor shaft: the whole inertia Tredgold asks for
    flywheel_inertia_tredgold: float  # kg*m^2 on the flywheel's shaft
    flywheel_inertia: float  # kg*m^2 on the flywheel's shaft: the simulation meets the target with it
    irregularity_with_tredgold_flywheel: float
    irregularity_with_flywheel: float  # the check run's delta with ``flywheel_inertia``
    flywheel_as_given: float  # kg*m^2: the scenario's own flywheel (0 without one)
    irregularity_as_given: float  # the machine as the scenario gives it: simulated ...
    irregularity_tredgold_as_given: float  # ... and by Tredgold
    shaft_ratio: float  # the flywheel shaft's speed per unit motor speed
    candidates: np.ndarray = field(default_factory=lambda: np.zeros(0))  # kg*m^2 on the flywheel's shaft
    candidate_irregularity: np.ndarray = field(default_factory=lambda: np.zeros(0))
    rim: dict | None = None

    def irregularity_tredgold(self, flywheel_inertia):
        """Tredgold's delta with a flywheel of this inertia on its shaft."""
        whole = self.machine_inertia + np.asarray(flywheel_inertia) * self.shaft_ratio**2
        return self.energy_fluctuation / (whole * self.mean_speed**2)

    def as_dict(self) -> dict:
        out = {
            "shaft": self.shaft,
            "irregularity": self.irregularity,
            "mean_speed": self.mean_speed,
            "energy_fluctuation": self.energy_fluctuation,
            "machine_inertia": self.machine_inertia,
            "required_inertia_tredgold": self.required_inertia_tredgold,
            "flywheel_inertia_tredgold": self.flywheel_inertia_tredgold,
            "flywheel_inertia": self.flywheel_inertia,
            "irregularity_with_tredgold_flywheel": self.irregularity_with_tredgold_flywheel,
            "irregularity_with_flywheel": self.irregularity_with_flywheel,
            "flywheel_as_given": self.flywheel_as_given,
            "irregularity_as_given": self.irregularity_as_given,
            "irregularity_tredgold_as_given": self.irregularity_tredgold_as_given,
        }
        if self.rim is not None:
            out["rim"] = self.rim
        return out


def with_flywheel(scenario, shaft: str, inertia: float, start: dict | None = None):
    """The scenario with its flywheel replaced by one of this inertia on ``shaft``.

    ``start``: the bare run's regime (mean speed, the mean of Tredgold's
    energy curve, the machine's inertia and its gear ratio, a duration): the
    run then starts on Tredgold's periodic orbit for this flywheel, where the
    speed at a period's start satisfies 1/2 I w^2 = 1/2 I w_m^2 + E(0) - mean(E),
    E(0) = 0, so that only what the motor's characteristic changes is left to
    settle, and lasts long enough for that (see :func:`_settling_duration`).
    """
    update = {"flywheel": FlywheelSpec(shaft=shaft, inertia=float(inertia)), "sweep": None}
    if start is not None:
        whole = start["inertia"] + float(inertia) * start["shaft_ratio"] ** 2
        speed = math.sqrt(max(start["mean_speed"] ** 2 - 2 * start["energy_mean"] / whole, 0.0))
        update["initial"] = InitialSpec(motor_speed=speed, drum_speed=speed * start["drum_ratio"])
        update["simulation"] = scenario.simulation.model_copy(update={"duration": start["duration"]})
    return scenario.model_copy(update=update)


def _settling_duration(scenario, reference, given: float, shaft_ratio: float, inertias) -> float:
    """A duration in which every candidate settles, from how fast the reference run's transient died away.

    Its changes from period to period shrank by a factor q each period: a time
    constant tau = -T / ln q.  Another flywheel makes the machine's inertia,
    and so the time constant, (I_machine + I r^2) / (I_machine + I_given r^2)
    times as large.  A run that starts on Tredgold's orbit is left with a
    transient of about 1e-3 of the speed (what Tredgold's orbit misses), which
    must shrink to the settling tolerance: ln(1e-3 / tolerance) time constants.
    """
    values, table = reference.values, reference.periodic.regime.table
    whole = values["inertia_tredgold"]
    own = whole - given * shaft_ratio**2
    period_time = values["period"] / values["mean_speed"]
    changes = np.abs(np.diff(table["mean_speed"])) / values["mean_speed"]
    useful = changes > reference.periodic.regime.tolerance / 100  # above round-off
    shrink = changes[1:][useful[1:] & useful[:-1]] / changes[:-1][useful[1:] & useful[:-1]]
    q = float(np.clip(np.median(shrink), 0.01, 0.99)) if shrink.size else 0.5
    tau = -period_time / math.log(q)
    longest = max((own + float(i) * shaft_ratio**2) / whole for i in inertias)
    analysed = (scenario.periodic_regime.periods + 3) * period_time
    constants = math.log(max(1e-3 / reference.periodic.regime.tolerance, math.e))
    return constants * tau * max(longest, 1.0) + analysed


def _irregularities(scenario, shaft: str, inertias, start: dict | None = None) -> tuple[list[dict], np.ndarray]:
    """Run the scenario with each flywheel (one vectorised call): summaries, and delta (NaN: not settled)."""
    inertias = [float(i) for i in inertias]
    scenarios = [with_flywheel(scenario, shaft, i, start) for i in inertias]
    # every call one chunk of the same width: one compiled program for all of them
    summaries = simulate_many(scenarios, [f"{i:.6g} kg*m^2" for i in inertias], summary_only=True,
                              chunk_size=CANDIDATES)
    return summaries, np.asarray([s["irregularity"] for s in summaries], dtype=float)


def _not_settled(scenario, inertia: float, reference: bool = False) -> ScenarioError:
    if reference:
        return ScenarioError("simulation.duration", f"the periodic regime of the machine as given (flywheel "
                             f"{inertia:.6g} kg*m^2) has not settled within {scenario.simulation.duration:g} s: "
                             "raise simulation.duration, or give a flywheel with which the machine runs "
                             "(flywheel.inertia) to start from")
    return ScenarioError("simulation.duration", f"with a flywheel of {inertia:.6g} kg*m^2 the periodic regime "
                         f"does not settle in the time allowed; raise simulation.duration "
                         f"(now {scenario.simulation.duration:g} s)")


def size_flywheel(scenario, irregularity: float) -> Sizing:
    """Tredgold's flywheel and the simulation's for a degree of irregularity (see the module docstring).

    The machine as given (with its own flywheel, if it has one) is run first:
    its regime gives the mean speed, Tredgold's Delta E_max and how fast a
    transient dies away; the machine's own inertia is its constant inertia
    less that flywheel's.
    """
    if not 0.0 < irregularity < 1.0:
        raise ScenarioError("--irregularity", f"must be between 0 and 1 (a fraction: 0.01 for 1 %), got {irregularity:g}")
    if scenario.periodic_regime is None:
        raise ScenarioError("motor.ripple", "the machine has no periodic regime to size a flywheel for: "
                            "give motor.ripple, drum.resisting_ripple or reciprocating")
    shaft = scenario.flywheel.shaft if scenario.flywheel is not None else "motor"
    given = scenario.flywheel.moment_of_inertia if scenario.flywheel is not None else 0.0
    drum_ratio = scenario.gears.pinion_teeth / scenario.gears.wheel_teeth
    ratio = 1.0 if shaft == "motor" else drum_ratio
    reference = simulation.simulate(with_flywheel(scenario, shaft, given))
    if reference.periodic.diagram is None:
        raise _not_settled(scenario, given, reference=True)
    values = reference.values
    mean, energy = values["mean_speed"], values["energy_fluctuation_tredgold"]
    own = values["inertia_tredgold"] - given * ratio**2
    required = energy / (irregularity * mean**2)
    tredgold = max(0.0, (required - own) / ratio**2)
    sizing = Sizing(shaft=shaft, irregularity=irregularity, mean_speed=mean, energy_fluctuation=energy,
                    machine_inertia=own, required_inertia_tredgold=required, flywheel_inertia_tredgold=tredgold,
                    flywheel_inertia=math.nan, irregularity_with_tredgold_flywheel=math.nan,
                    irregularity_with_flywheel=math.nan, flywheel_as_given=given,
                    irregularity_as_given=values["irregularity"],
                    irregularity_tredgold_as_given=values["irregularity_tredgold"], shaft_ratio=ratio)
    known_inertia, known_delta = np.asarray([given]), np.asarray([values["irregularity"]])
    scale = max(tredgold, own / ratio**2 * 1e-3)
    candidates, deltas, start = [], [], None
    for low_factor, high_factor in (SPREAD, WIDE_SPREAD):
        # Tredgold's flywheel and a spread about it (a damping motor needs less, reciprocating parts more)
        trial = np.concatenate([[tredgold], scale * np.geomspace(low_factor, high_factor, CANDIDATES - 1)])
        start = {"mean_speed": mean, "energy_mean": reference.periodic.diagram.mean_energy, "inertia": own,
                 "shaft_ratio": ratio, "drum_ratio": drum_ratio,
                 "duration": _settling_duration(scenario, reference, given, ratio, trial)}
        _, delta = _irregularities(scenario, shaft, trial, start)
        candidates.append(trial)
        deltas.append(delta)
        if np.nanmin(delta) <= irregularity < np.nanmax(np.concatenate([known_delta, delta])):
            break
    sizing.irregularity_with_tredgold_flywheel = float(deltas[0][0])
    if tredgold == 0.0 and deltas[0][0] <= irregularity:  # the machine meets the target on its own
        sizing.flywheel_inertia, sizing.irregularity_with_flywheel = 0.0, float(deltas[0][0])
        return _with_curve(sizing, candidates, deltas, known_inertia, known_delta)

    def answer():
        """1/delta is close to linear in the flywheel's inertia: interpolate it between the bracket."""
        low, high = _bracket(np.concatenate([known_inertia, *candidates]), np.concatenate([known_delta, *deltas]),
                             irregularity, scenario)
        inverse = (1 / low[1], 1 / high[1])
        return low[0] + (1 / irregularity - inverse[0]) * (high[0] - low[0]) / (inverse[1] - inverse[0])

    first = answer()
    trial = first * (1 + REFINE * np.linspace(-1, 1, CANDIDATES))
    _, delta = _irregularities(scenario, shaft, trial, start)
    candidates.append(trial)
    deltas.append(delta)
    final = answer()
    _, check = _irregularities(scenario, shaft, [final], start)
    sizing.flywheel_inertia = float(final)
    sizing.irregularity_with_flywheel = float(check[0])
    return _with_curve(sizing, candidates, deltas, np.concatenate([known_inertia, [final]]),
                       np.concatenate([known_delta, check]))


def _bracket(inertias, deltas, target, scenario):
    """The two candidates either side of the target: (inertia, delta) with delta above, and below."""
    order = np.argsort(inertias)
    inertias, deltas = np.asarray(inertias)[order], np.asarray(deltas)[order]
    unsettled = ~np.isfinite(deltas)
    above = np.flatnonzero((deltas > target) & ~unsettled)
    below = np.flatnonzero((deltas <= target) & ~unsettled)
    if below.size == 0:
        if unsettled.any():
            raise _not_settled(scenario, float(inertias[unsettled][0]))
        raise ScenarioError("--irregularity", f"even a flywheel of {inertias[-1]:.6g} kg*m^2 leaves delta at "
                            f"{deltas[-1]:.4g}, above {target:g}: the target is out of reach of a flywheel "
                            "(the motor's characteristic or the clutch limits it)")
    j = below[0]
    i = above[above < j][-1] if (above < j).any() else None
    if i is None:
        raise ScenarioError("--irregularity", f"delta is already below {target:g} with the smallest flywheel tried "
                            f"({inertias[0]:.6g} kg*m^2)")
    if unsettled[i:j + 1].any():
        raise _not_settled(scenario, float(inertias[i:j + 1][unsettled[i:j + 1]][0]))
    return (inertias[i], deltas[i]), (inertias[j], deltas[j])


def _with_curve(sizing: Sizing, candidates, deltas, extra_inertias, extra_deltas) -> Sizing:
    inertias = np.concatenate([*candidates, np.asarray(extra_inertias, float)])
    values = np.concatenate([*deltas, np.asarray(extra_deltas, float)])
    order = np.argsort(inertias)
    sizing.candidates, sizing.candidate_irregularity = inertias[order], values[order]
    return sizing


def rim(inertia: float, density: float, *, width: float | None = None, outer_diameter: float | None = None,
        inner_diameter: float = 0.0) -> dict:
    """The rim (or disc, inner diameter 0) of this inertia: I = pi rho s (R_o^4 - R_i^4) / 2.

    Give the width to get the outer diameter, or the outer diameter to get the width.
    """
    inner = 0.5 * inner_diameter
    if (width is None) == (outer_diameter is None):
        raise ScenarioError("--width", "give either --width or --outer-diameter with --density")
    if width is not None:
        outer = (2 * inertia / (math.pi * density * width) + inner**4) ** 0.25
    else:
        outer = 0.5 * outer_diameter
        if outer <= inner:
            raise ScenarioError("--outer-diameter", f"must exceed the inner diameter ({inner_diameter:g} m)")
        width = 2 * inertia / (math.pi * density * (outer**4 - inner**4))
    return {"density": density, "outer_diameter": 2 * outer, "inner_diameter": inner_diameter, "width": width,
            "mass": density * math.pi * (outer**2 - inner**2) * width, "inertia": inertia}

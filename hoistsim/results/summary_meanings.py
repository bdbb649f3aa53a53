"""What each summary of a run means, in words: the ``long_name`` a results file gives its summary variables, and
the ``comment`` saying what a value of 0 or NaN stands for where it stands for something (a lock-up at 0: the
clutch was locked from the start; NaN: it never locked); and the words of the numbers a file holds beside the summary (the
energy ledger's terms, the solver's counts).

A summary's name is made by its part from a pattern (``{name}_lockup_time``, ``final_{name}_speed``), so its
meaning is read from the pattern here, the part's name filled in; the hoist's template gives some the names of
its exercise (``lockup_time``, ``peak_clutch_torque``), listed by name.  A part's new summary without words here
fails tests/results/test_output.py, which reads every shipped scenario's.  The reductions behind the words (the
core's ``first`` is NaN until its condition first holds, and the time it holds at t = 0 is 0) are in
:mod:`hoistsim.machine.core.loop`.
"""

from __future__ import annotations

import re

# what a "first" reduction's 0 and NaN say of a clutch's lock (0 is no promise it never slips later)
_FIRST_LOCK = "0: locked from the start (with a slip_duration of 0: never slipped); NaN: never locked in the run"
_NEVER_SLIPPED = "0: never slipped"

# the hoist template's names: name -> (long_name, comment)
_NAMED = {
    "lockup_time": ("time the clutch first locks", _FIRST_LOCK),
    "slip_duration": ("time the clutch spends slipping", _NEVER_SLIPPED),
    "slip_energy": ("heat dissipated in the clutch over the run", _NEVER_SLIPPED),
    "peak_clutch_torque": ("largest torque the clutch passes (magnitude)", ""),
    "peak_slip_speed": ("largest slip speed of the clutch (magnitude)", _NEVER_SLIPPED),
    "peak_clutch_temperature": ("highest temperature of the clutch's faces", ""),
    "final_clutch_temperature": ("temperature of the clutch's faces at the end", ""),
    "overheat_time": ("time the clutch's faces first reach their limit temperature", "NaN: never reached"),
    "lowest_load_position": ("lowest position of the load (up positive, 0 where it starts)", ""),
    "final_load_position": ("position of the load at the end (up positive, 0 where it starts)", ""),
    "load_lifted": ("the load ends above where it started", "1: yes, 0: no"),
    "peak_rope_force": ("largest rope force", ""),
    "dynamic_factor": ("dynamic factor: largest rope force over the load's weight", ""),
    "lift_off_time": ("time the load first lifts off the ground",
                      "0: lifted at the start (the ground held nothing); NaN: never lifted off"),
    "landing_loss": ("kinetic energy lost as the load lands on the ground", "0: never landed (or landed at rest)"),
    "dynamic_factor_standard": ("EN 13001-2's dynamic factor phi2 for the rope speed at lift-off",
                                "NaN: never lifted off"),
    "peak_buffer_force": ("largest push of the buffer on the load", "0: never reached"),
    "peak_buffer_compression": ("furthest the load presses the buffer in", "0: never reached"),
    "buffer_impact_speed": ("speed of the load, down positive, where it first meets the buffer", "NaN: never reached"),
    "buffer_force_standard": ("EN 13001-2's design buffer force for that impact: phi7 (1.25, a linear buffer) times "
                              "the rigid-body force M g + sqrt((M g)^2 + k_b M v^2)", "NaN: never reached"),
    "lock_events": ("number of lock instants (a coupling sticking) in the run's events", ""),
    "unlock_events": ("number of unlock instants (a coupling breaking loose) in the run's events", ""),
    "energy_residual": ("energy balance's residual: work done less the energy stored and lost", ""),
    "energy_relative_residual": ("energy balance's residual (magnitude) over its largest term", ""),
    "heat_relative_residual": ("heat balance's residual over the loss it accounts for", ""),
    # the periodic regime of the motor shaft (NaN: no settled regime, settling_periods -1)
    "period": ("angle of the machine's cycle: a period of the motor shaft", ""),
    "settling_periods": ("whole periods before the regime settled", "-1: never settled"),
    "mean_speed": ("mean speed over angle of the motor shaft, settled regime", "NaN: never settled"),
    "max_speed": ("highest speed of the motor shaft, settled regime", "NaN: never settled"),
    "min_speed": ("lowest speed of the motor shaft, settled regime", "NaN: never settled"),
    "max_speed_angle": ("angle within the period of the highest speed", "NaN: never settled"),
    "min_speed_angle": ("angle within the period of the lowest speed", "NaN: never settled"),
    "irregularity": ("degree of irregularity (max - min speed) / mean speed, simulated", "NaN: never settled"),
    "irregularity_tredgold": ("degree of irregularity by Tredgold's approximation", "NaN: never settled"),
    "energy_fluctuation": ("largest fluctuation of the kinetic energy in a period, simulated",
                           "NaN: never settled"),
    "energy_fluctuation_tredgold": ("largest energy fluctuation in a period by Tredgold's approximation",
                                    "NaN: never settled"),
    "inertia_tredgold": ("inertia at the motor shaft by Tredgold's approximation", "NaN: never settled"),
    "switches_per_period": ("mean switches of the couplings in a period, settled regime", "NaN: never settled"),
    # a drive's brake sequence (the scene has one)
    "rollback_distance": ("rope the drum pays out backwards from the brake's release until the drive has the load "
                          "going its way", "0: no rollback"),
    "stopping_time": ("time from the emergency stop until the brake holds the drum", "NaN: not held by the end"),
    "stopping_distance": ("rope the drum pays out from the emergency stop until the brake holds it", ""),
}

# a part's own names, its name filled in: pattern -> (long_name, comment), first match wins
_PATTERNS = [
    (r"(?P<part>.+)_lockup_time", "time {part} first locks", _FIRST_LOCK),
    (r"(?P<part>.+)_slip_duration", "time {part} spends slipping", _NEVER_SLIPPED),
    (r"(?P<part>.+)_slip_energy", "heat dissipated in {part} over the run", _NEVER_SLIPPED),
    (r"(?P<part>.+)_peak_torque", "largest torque {part} passes (magnitude)", ""),
    (r"(?P<part>.+)_max_torque", "largest torque of {part} (signed: its most forwards)", ""),
    (r"(?P<part>.+)_min_torque", "least torque of {part} (signed: its most backwards)", ""),
    (r"(?P<part>.+)_peak_current", "largest current of {part} (magnitude; an induction machine's stator space "
                                   "phasor's)", ""),
    (r"(?P<part>.+)_saturated_time", "time controller {part} spends at a limit of its output", "0: never"),
    (r"(?P<part>.+)_proven_torque", "torque drive {part} had proven when its brake let go",
     "NaN: never released"),
    (r"(?P<part>.+)_release_time", "time drive {part}'s brake lets go", "NaN: never released"),
    (r"(?P<part>.+)_(?P<end>lower|upper)_impact_loss", "kinetic energy taken by the {end} stop of {part} in its "
                                                       "impacts over the run", "0: never struck (or struck at rest)"),
    (r"(?P<part>.+)_peak_friction", "largest friction force {part} passes (magnitude)", ""),
    (r"(?P<part>.+)_peak_slip_speed", "largest slip speed of {part} (magnitude)", _NEVER_SLIPPED),
    (r"(?P<part>.+)_overheat_time", "time {part} first reaches its limit temperature", "NaN: never reached"),
    (r"peak_(?P<part>.+)_temperature", "highest temperature of {part}", ""),
    (r"final_(?P<part>.+)_temperature", "temperature of {part} at the end", ""),
    (r"final_(?P<part>.+)_speed", "speed of the {part} shaft at the end", ""),
    (r"final_(?P<part>.+)_velocity", "velocity of mass {part} at the end", ""),
    (r"(?P<part>.+)_per_period", "mean growth of {part} in a period, settled regime", "NaN: never settled"),
    (r"(?P<part>.+)_loss_energy", "energy lost in {part} over the run", ""),
    (r"(?P<part>.+)_energy", "heat dissipated in {part} over the run", ""),
]


def summary_meaning(name: str) -> tuple[str, str]:
    """(long_name, comment) of the summary ``name``; the comment says what 0 or NaN stand for ("" where they
    are plain numbers).  A sensitivity's ``d_<summary>_d_<key>`` is the summary's derivative.  ("", "") for
    a name no part makes."""
    if name in _NAMED:
        return _NAMED[name]
    if name.startswith("d_") and "_d_" in name[2:]:
        summary, _, key = name[2:].rpartition("_d_")
        what = summary_meaning(summary)[0] or summary
        return f"derivative of the {what} with respect to {key}", "NaN: none (the summary itself is none)"
    for pattern, text, comment in _PATTERNS:
        found = re.fullmatch(pattern, name)
        if found:
            return text.format(**found.groupdict()), comment
    return "", ""


# the solver's counts a run's file holds beside its summary (``solver_<count>``)
_SOLVER = {"steps": "accepted steps of the solver", "rejected_steps": "steps the solver rejected and retried",
           "segments": "segments run between switches", "switches": "switches located (locks, unlocks, ...)",
           "wall_time": "wall-clock time of the run"}


def extra_meaning(name: str) -> str:
    """The long_name of a number a file holds beside the summary: an energy ledger term over the run
    (``energy_<term>``, its residuals) or a solver count (``solver_<count>``); "" for another name."""
    if name.startswith("solver_"):
        return _SOLVER.get(name[len("solver_"):], "")
    if not name.startswith("energy_"):
        return ""
    term = name[len("energy_"):]
    if term == "heat_residual":
        return "heat balance's residual: the heat the parts account for less the loss"
    if term.endswith("residual"):
        return summary_meaning(term if term.startswith("heat") else name)[0]
    if term.endswith("_change"):  # a stored energy: what the run changed it by
        return f"energy ledger: change of the {term.removesuffix('_change').replace('_', ' ')} over the run"
    return f"energy ledger: {term.replace('_', ' ')} over the run"

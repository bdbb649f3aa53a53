"""What a fit can and cannot claim: which keys the trace determines, and whether its residuals are the noise.

A key the trace does not see has no standard error and no interval.  Its
column of the Jacobian may be zero (a slipping clutch passes the same torque
whatever load it drives: the motor's speed does not depend on the load's
mass), or the keys' columns may be dependent (a clutch's force and its
friction move a slipping clutch's torque only as their product): then the
information matrix JᵀJ is singular, and (JᵀJ)⁻¹ says nothing true.  Both are
read from the singular values of the Jacobian with each column scaled to its
key's value and then to unit length, so that neither a key's unit nor its
size decides.

Residuals that are the noise are as large as the noise and do not keep their
sign for long.  The noise is estimated from the residuals themselves: from
the differences of successive residuals (a slow pattern, what a wrong model
leaves, mostly cancels in them; their median absolute deviation ignores the
few rows where a switch falls between the fitted and the measured times).
A residual RMS well above that noise, or fewer runs of one sign than noise
gives (Wald and Wolfowitz's runs test), says the fitted run does not explain
the trace.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

# A column this small against the largest (each scaled to its key's value) is zero: the trace does not see it.
ZERO_COLUMN = 1e-8
# Unit-length columns whose smallest singular value is this small against the largest are dependent (JᵀJ's
# condition the square of its inverse: 1e12, where its inverse is round-off); a key weighing this much in
# such a singular vector is one the trace cannot tell apart from the others of it.
SINGULAR = 1e-6
IN_COMBINATION = 0.2
# A residual RMS this many times the noise says the fit does not explain the trace (the RMS of noise alone
# is the noise to a few per cent, with hundreds of rows).
NOISE_RATIO = 1.5
# The runs test's z below this (fewer runs of one sign than noise gives, p < 0.0014): the residuals are
# patterned.
RUNS_Z = -3.0

# Why a key whose column is zero is undetermined.
NOT_SEEN = "the trace does not depend on it here (its column of the Jacobian is zero)"


def undetermined(jacobian: np.ndarray, values: np.ndarray, keys: list[str]) -> dict[str, str]:
    """The keys the trace does not determine at ``values`` (``jacobian``: the weighted residuals' derivatives,
    rows by keys), each with why."""
    scale = np.where(values != 0, np.abs(values), 1.0)
    columns = jacobian * scale
    norms = np.linalg.norm(columns, axis=0)
    top = float(np.max(norms)) if norms.size else 0.0
    reasons = {}
    zero = norms <= ZERO_COLUMN * top if top > 0 else np.ones(len(keys), bool)
    for k in np.flatnonzero(zero):
        reasons[keys[k]] = NOT_SEEN
    seen = np.flatnonzero(~zero)
    if seen.size < 2:
        return reasons
    _, s, vt = np.linalg.svd(columns[:, seen] / norms[seen], full_matrices=False)
    small = s < SINGULAR * s[0]
    if not np.any(small):
        return reasons
    involved = seen[np.any(np.abs(vt[small]) >= IN_COMBINATION, axis=0)]
    condition = (s[0] / max(s[-1], np.finfo(float).tiny)) ** 2
    names = [keys[k] for k in involved]
    for key in names:
        others = " and ".join(name for name in names if name != key)
        reasons[key] = (f"the trace sees it only in a combination with {others} (the information matrix JᵀJ is "
                        f"singular, condition {condition:.1e})")
    return reasons


@dataclasses.dataclass
class ResidualCheck:
    """A matched series' residuals against the noise: all in the series' SI unit."""

    rms: float
    noise: float  # estimated from successive residuals
    runs: int  # runs of one sign
    expected_runs: float  # what noise would give
    runs_z: float
    lag1: float  # the residuals' correlation with the next row's

    @property
    def far_from_noise(self) -> bool:
        return self.rms > NOISE_RATIO * self.noise

    @property
    def patterned(self) -> bool:
        return self.runs_z < RUNS_Z

    def to_dict(self) -> dict:
        return {"rms": self.rms, "noise": self.noise, "runs": self.runs, "expected_runs": self.expected_runs,
                "lag1_correlation": self.lag1}


def residual_check(residual: np.ndarray) -> ResidualCheck:
    """The residuals' RMS, the noise estimated from them, their runs test and lag-1 correlation."""
    r = np.asarray(residual, dtype=float)
    rms = float(np.sqrt(np.mean(r ** 2)))
    steps = np.diff(r)
    # successive differences of white noise of deviation s have deviation s sqrt(2); the MAD's factor makes
    # it a deviation for normal data
    noise = 1.4826 * float(np.median(np.abs(steps - np.median(steps)))) / math.sqrt(2.0) if steps.size else 0.0
    signs = np.sign(r)
    signs = signs[signs != 0]
    above, below = int(np.sum(signs > 0)), int(np.sum(signs < 0))
    total = above + below
    runs = 1 + int(np.sum(signs[1:] != signs[:-1])) if total else 0
    expected = 2.0 * above * below / total + 1.0 if total else 0.0
    variance = (expected - 1.0) * (expected - 2.0) / (total - 1.0) if total > 1 else 0.0
    z = (runs - expected) / math.sqrt(variance) if variance > 0 else 0.0
    centred = r - np.mean(r)
    power = float(centred @ centred)
    lag1 = float(centred[:-1] @ centred[1:]) / power if power > 0 else 0.0
    return ResidualCheck(rms=rms, noise=noise, runs=runs, expected_runs=expected, runs_z=z, lag1=lag1)


def residual_warnings(name: str, check: ResidualCheck, shown) -> list[str]:
    """What a series' residuals say against the fit, one line each; ``shown``: an SI amount of the series ->
    text in the trace's unit."""
    lines = []
    if check.far_from_noise:
        ratio = check.rms / check.noise if check.noise > 0 else math.inf
        times = f"{ratio:.0f} times" if math.isfinite(ratio) else "far above"
        lines.append(f"{name}: the residual RMS {shown(check.rms)} is {times} the noise ({shown(check.noise)}, "
                     "estimated from successive residuals): the fitted run does not explain the trace")
    if check.patterned:
        lines.append(f"{name}: the residuals are patterned ({check.runs} runs of one sign where noise would give "
                     f"{check.expected_runs:.0f}; lag-1 correlation {check.lag1:.2f}): the model misses "
                     "something the trace shows")
    return lines

"""A time signal on an element: its table among the run's tables, its harmonics evaluated at the instant."""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np


def signal_fields(signal, prefix: str) -> dict:
    """The element fields of a :class:`hoistsim.scenario.signals.TimeSignal`: ``<prefix>_times`` and ``_values`` (a
    table of time, whose knots are segment boundaries) and the harmonics' amplitudes, frequencies, phases."""
    return {f"{prefix}_times": np.asarray(signal.times, float), f"{prefix}_values": np.asarray(signal.values, float),
            f"{prefix}_amplitudes": np.asarray(signal.amplitudes, float),
            f"{prefix}_frequencies": np.asarray(signal.frequencies, float),
            f"{prefix}_phases": np.asarray(signal.phases, float)}


def harmonics_at(t, amplitudes, frequencies, phases):
    """sum A sin(2 pi f t + phi) (0 with no harmonics: no term is traced)."""
    if amplitudes.shape[0] == 0:
        return 0.0
    return jnp.sum(amplitudes * jnp.sin(2.0 * jnp.pi * frequencies * t + phases))

"""A time signal on an element: its table among the run's tables, its harmonics evaluated at the instant."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

from ..core.schedule import table_at


def signal_fields(signal, prefix: str) -> dict:
    """The element fields of a :class:`hoistsim.scenario.signals.TimeSignal`: ``<prefix>_times`` and ``_values`` (a
    table of time, whose knots are segment boundaries), the harmonics' amplitudes, frequencies, phases, and
    their envelope's ``<prefix>_envelope_times`` and ``_values`` (a table of time too; None: no envelope)."""
    enveloped = signal.envelope_times is not None
    return {f"{prefix}_times": np.asarray(signal.times, float), f"{prefix}_values": np.asarray(signal.values, float),
            f"{prefix}_amplitudes": np.asarray(signal.amplitudes, float),
            f"{prefix}_frequencies": np.asarray(signal.frequencies, float),
            f"{prefix}_phases": np.asarray(signal.phases, float),
            f"{prefix}_envelope_times": np.asarray(signal.envelope_times, float) if enveloped else None,
            f"{prefix}_envelope_values": np.asarray(signal.envelope_values, float) if enveloped else None}


def signal_tables(element, prefix: str) -> dict:
    """The tables of time of an element's signal ``prefix`` (as ``tables()`` gives them): its table, named
    ``<section>.<prefix>``, and its envelope's, ``<section>.<prefix>_envelope``, where it has one."""
    tables = {f"{element.section}.{prefix}": (f"{prefix}_times", f"{prefix}_values")}
    if getattr(element, f"{prefix}_envelope_times") is not None:
        tables[f"{element.section}.{prefix}_envelope"] = (f"{prefix}_envelope_times", f"{prefix}_envelope_values")
    return tables


def signal_at(element, x, prefix: str):
    """The element's signal ``prefix`` at the instant: its table plus its harmonics, times their envelope."""
    harmonics = harmonics_at(x.t, getattr(element, f"{prefix}_amplitudes"), getattr(element, f"{prefix}_frequencies"),
                             getattr(element, f"{prefix}_phases"))
    if getattr(element, f"{prefix}_envelope_times") is not None:
        harmonics = x.table(f"{element.section}.{prefix}_envelope") * harmonics
    return x.table(f"{element.section}.{prefix}") + harmonics


def harmonics_step(element, prefix: str):
    """The longest step the harmonics of an element's signal ``prefix`` allow (s): an eighth of their shortest
    period, so that every quarter swing has a step's end in it; None where it has none (or no such signal)."""
    frequencies = getattr(element, f"{prefix}_frequencies")
    if frequencies is None or frequencies.shape[0] == 0:
        return None
    return 1.0 / (8.0 * jnp.max(jnp.abs(frequencies)))


def harmonics_at(t, amplitudes, frequencies, phases):
    """sum A sin(2 pi f t + phi) (0 with no harmonics: no term is traced)."""
    if amplitudes.shape[0] == 0:
        return 0.0
    return jnp.sum(amplitudes * jnp.sin(2.0 * jnp.pi * frequencies * t + phases))


class _Reading:
    """An instant's tables read at a time ``t`` of one's choosing: what :func:`signal_at` needs of an instant."""

    def __init__(self, table, t):
        self.t = t
        self._table = table

    def table(self, name):
        return self._table(name, self.t)


def signal_derivatives(element, x, prefix: str, order: int) -> list:
    """The element's signal ``prefix`` and its first ``order`` derivatives in time at the instant, exact: over a
    segment its table is one line (its slope the first derivative, no second), its harmonics differentiated
    as they are traced."""
    def value(t):
        return signal_at(element, _Reading(x.table_at, t), prefix)

    found = [value]
    for _ in range(order):
        found.append(lambda t, f=found[-1]: jax.jvp(f, (t,), (jnp.ones_like(t),))[1])
    t = jnp.asarray(x.t, dtype=jnp.float64)
    return [f(t) for f in found]


def signal_start(element, prefix: str):
    """The element's signal ``prefix`` at t = 0, read from its fields (an initial state's value)."""
    tables = element.tables()

    def table(name, t):
        times, values = tables[name]
        return table_at(getattr(element, times), getattr(element, values), t)

    return signal_at(element, _Reading(table, 0.0), prefix)

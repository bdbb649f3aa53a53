"""What the compiled loop returns, and reading it back on the host by name: columns, events, summary, ledger."""

from __future__ import annotations

import jax
import numpy as np

from ..._pytree import pytree_dataclass
from .layout import Layout
from .ledger import HELD, PEAK_TERM

EVENT_COUNT, SWITCHES, STATUS, STEPS, REJECTED, PASSES, KEPT_STEPS, STEP_ROOM = range(8)


@pytree_dataclass
class RawRun:
    """What the compiled loop returns, packed into few arrays (each costs a transfer to the host).

    :class:`Readout` reads it back by name.
    """

    grid_state: jax.Array  # (rows, states)
    grid_modes: jax.Array  # (rows, couplings)
    grid_columns: jax.Array  # (columns, rows), in the order of Layout.columns()
    event_columns: jax.Array  # (columns, events)
    event_times: jax.Array  # (events, 2): time (NaN where unused), margin (N*m: capacity less |stuck torque|)
    event_codes: jax.Array  # (events, 2): kind (Layout.event_kinds), element (Layout.sections)
    event_state: jax.Array
    event_modes: jax.Array
    final_state: jax.Array
    scalars: jax.Array  # end time, then Layout.summaries, then each ledger term at the start and the end
    counters: jax.Array  # event count, switches, status, steps, rejected steps, passes, steps kept, room
    kind_counts: jax.Array  # events of each kind (Layout.event_kinds), however small the log


class _Lane:
    """Run ``k`` of a batch: each field of the batch's RawRun indexed at k when read."""

    def __init__(self, raw, k: int):
        self._raw, self._k = raw, k

    def __getattr__(self, name):
        return getattr(self._raw, name)[self._k]


class Readout:
    """One run's :class:`hoistsim.machine.core.loop.RawRun` (numpy arrays, on the host) read through its layout.

    ``lane`` picks one run of a batch (a vmapped sweep's chunk).
    """

    def __init__(self, layout: Layout, raw, lane: int | None = None):
        self.layout = layout
        self.raw = raw if lane is None else _Lane(raw, lane)

    def _count(self, which: int) -> int:
        return int(self.raw.counters[which])

    @property
    def status(self) -> int:
        return self._count(STATUS)

    @property
    def event_count(self) -> int:
        return self._count(EVENT_COUNT)

    @property
    def end_time(self) -> float:
        return float(self.raw.scalars[0])

    @property
    def stats(self) -> dict:
        return {"steps": self._count(STEPS), "rejected_steps": self._count(REJECTED),
                "segments": self._count(PASSES), "switches": self._count(SWITCHES)}

    def _cast(self, name: str, values: np.ndarray) -> np.ndarray:
        # a column in units "1" is a flag or a mode (see AbstractElement)
        return values.astype(np.int8) if self.layout.columns()[name][0] == "1" else values

    def columns(self, rows: int) -> dict[str, np.ndarray]:
        """Every output column on the first ``rows`` grid rows followed by the event rows."""
        events = self.event_count
        grid, at_events = np.asarray(self.raw.grid_columns), np.asarray(self.raw.event_columns)
        return {name: self._cast(name, np.concatenate([grid[i, :rows], at_events[i, :events]]))
                for i, name in zip(self.layout.column_slots, self.layout.columns())}

    def events(self) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Times, kinds, elements and torque margins of every logged event (observations included)."""
        n = self.event_count
        codes = np.asarray(self.raw.event_codes[:n])
        kinds = np.asarray([self.layout.event_kinds[int(k)] for k in codes[:, 0]], dtype=object)
        elements = np.asarray([self.layout.sections[int(e)] for e in codes[:, 1]], dtype=object)
        times = np.asarray(self.raw.event_times[:n], dtype=float)
        return times[:, 0], kinds, elements, times[:, 1]

    def event_rows(self) -> dict[str, np.ndarray]:
        """Every logged row (events and observations, in time order): its time and kind, each
        output column and each state by name."""
        n = self.event_count
        times, kinds, _, _ = self.events()
        values = np.asarray(self.raw.event_columns)[:, :n]
        rows = {name: values[i] for i, name in zip(self.layout.column_slots, self.layout.columns())}
        state = np.asarray(self.raw.event_state)[:n]
        rows.update({name: state[:, i] for i, name in enumerate(self.layout.state_names)})
        return {"time": times, "kind": kinds, **rows}

    @property
    def log_overflowed(self) -> bool:
        """Whether the run logged more rows than its log could keep (run it again with more)."""
        return self.event_count > np.asarray(self.raw.event_times).shape[-2]

    @property
    def steps_overflowed(self) -> bool:
        """Whether the run took more steps than it had room to keep for its rows (run it again with more)."""
        return self._count(KEPT_STEPS) > self._count(STEP_ROOM)

    @property
    def kept_steps(self) -> int:
        """The accepted steps the run kept for its rows (more than its room where it overflowed)."""
        return self._count(KEPT_STEPS)

    def count(self, kind: str) -> int:
        """How many events of a kind the run had (known even when the log kept no rows)."""
        return int(self.raw.kind_counts[self.layout.kind_code(kind)]) if kind in self.layout.event_kinds else 0

    def summary(self) -> dict:
        """The elements' summary values by name (yes/no values as bools)."""
        values = self.raw.scalars[1: 1 + self.layout.summary_count]
        return {name: bool(values[i]) if units == "bool" else float(values[i])
                for i, (name, units) in zip(self.layout.summary_slots, self.layout.summaries.items())}

    def ledger(self) -> dict:
        """Each energy term: name -> (kind, value at the start, value at the end)."""
        n, first = len(self.layout.ledger_kinds), 1 + self.layout.summary_count
        start = self.raw.scalars[first:][:n]
        end = self.raw.scalars[first + n:][:n]
        peak = self.raw.scalars[first + 2 * n]
        terms = {name: (kind, float(a), float(b))
                 for (name, kind), a, b in zip(self.layout.ledger_kinds.items(), start, end)}
        return terms | {PEAK_TERM: (HELD, 0.0, float(peak))}


class BatchReadout:
    """The first ``count`` runs of a batch's RawRun (a vmapped chunk), read column-wise: a value per run."""

    def __init__(self, layout: Layout, raw, count: int):
        self.layout, self.raw, self.count_runs = layout, raw, count

    def count(self, kind: str) -> np.ndarray:
        if kind not in self.layout.event_kinds:
            return np.zeros(self.count_runs, dtype=np.int64)
        return np.asarray(self.raw.kind_counts[: self.count_runs, self.layout.kind_code(kind)], dtype=np.int64)

    def summary(self) -> dict[str, np.ndarray]:
        """:meth:`Readout.summary` of every run: name -> values (yes/no values as bools)."""
        values = np.asarray(self.raw.scalars[: self.count_runs, 1: 1 + self.layout.summary_count])
        return {name: values[:, i].astype(bool) if units == "bool" else values[:, i].astype(float)
                for i, (name, units) in zip(self.layout.summary_slots, self.layout.summaries.items())}

    def ledger(self) -> dict:
        """:meth:`Readout.ledger` of every run: name -> (kind, starts, ends)."""
        n, first = len(self.layout.ledger_kinds), 1 + self.layout.summary_count
        scalars = np.asarray(self.raw.scalars[: self.count_runs])
        terms = {name: (kind, scalars[:, first + i], scalars[:, first + n + i])
                 for i, (name, kind) in enumerate(self.layout.ledger_kinds.items())}
        return terms | {PEAK_TERM: (HELD, np.zeros(self.count_runs), scalars[:, first + 2 * n])}

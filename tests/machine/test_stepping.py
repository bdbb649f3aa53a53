"""One pass stepped in one loop: the solver's own steps, the earliest crossing located exactly, the rows
written up to it, the implicit solvers too."""

from __future__ import annotations

from types import SimpleNamespace

import diffrax
import jax
import jax.numpy as jnp
import numpy as np
import pytest

from hoistsim.machine.core.kept_steps import no_steps, rows_from_steps
from hoistsim.machine.core.stepping import integrate_pass


def oscillator(t, y, args):
    """x'' = -x: from (1, 0), x = cos t, crossing zero at pi/2."""
    return jnp.stack([y[1], -y[0]])


def moving(t, y, args):
    """x' = 1: x = t."""
    return jnp.ones_like(y)


def solve(field, guards, y0, end, *, solver=diffrax.Tsit5(), rtol=1e-12, grid=None, max_steps=100_000, room=1024):
    """The pass, and (``grid_state``) its rows at ``grid`` from the steps it kept (room for ``room``)."""
    grid = np.array([end]) if grid is None else grid

    def go(y0):
        kept = no_steps(solver, y0, room=room, couplings=0)
        out = integrate_pass(solver, None, guards, 0.0, y0, end, rtol=rtol, atol=rtol * 1e-2, dtmax=jnp.inf,
                             max_steps=max_steps, kept=kept, count=0, modes=jnp.zeros((0,), int), field=field)
        return out, rows_from_steps(solver, out.kept, out.count, jnp.asarray(grid))[0]

    out, rows = jax.jit(go)(jnp.asarray(y0, dtype=float))
    return SimpleNamespace(**{name: getattr(out, name) for name in out.__dataclass_fields__}, grid_state=rows)


def test_a_crossing_is_found_on_the_interpolant_to_the_last_digits():
    out = solve(oscillator, lambda t, y, a: jnp.stack([y[0]]), [1.0, 0.0], 3.0)
    assert bool(out.hit) and list(np.asarray(out.mask)) == [True]
    assert float(out.t) == pytest.approx(np.pi / 2, abs=1e-11)
    np.testing.assert_allclose(np.asarray(out.y), [0.0, -1.0], atol=1e-11)
    assert float(oscillator(0, out.y, None)[0]) < 0  # past the root: a restart there does not meet it again
    assert float(out.y[0]) <= 0.0


def test_the_earliest_of_two_guards_crossing_in_one_step_ends_the_pass_whatever_their_order():
    # x' = 1 is solved exactly: each step is up to ten times the last (as the round-off of its error estimate
    # allows), so both guards cross in one step
    out = solve(moving, lambda t, y, a: jnp.stack([0.6 - y[0], 0.5 - y[0]]), [0.0], 1.0)
    assert int(out.steps) < 8
    assert float(out.t) == pytest.approx(0.5, abs=1e-14)
    assert list(np.asarray(out.mask)) == [False, True]


def test_without_a_crossing_the_pass_ends_at_its_end_and_agrees_with_the_closed_form():
    out = solve(oscillator, lambda t, y, a: jnp.stack([1.0 + 0.0 * t]), [1.0, 0.0], 10.0, rtol=1e-10)
    assert not bool(out.hit) and not bool(out.failed) and float(out.t) == 10.0
    np.testing.assert_allclose(np.asarray(out.y), [np.cos(10.0), -np.sin(10.0)], atol=1e-8)
    assert int(out.rejected) <= int(out.steps) // 10


def test_rows_before_the_crossing_are_written_and_none_after_it():
    grid = np.linspace(0.0, 1.0, 11)
    out = solve(moving, lambda t, y, a: jnp.stack([0.55 - y[0]]), [0.0], 1.0, grid=grid)
    rows = np.asarray(out.grid_state)[:, 0]
    np.testing.assert_allclose(rows[:6], grid[:6], atol=1e-14)
    assert np.isnan(rows[6:]).all()


def test_an_implicit_solver_steps_in_the_same_loop():
    out = solve(oscillator, lambda t, y, a: jnp.stack([y[0]]), [1.0, 0.0], 3.0, solver=diffrax.Kvaerno5(),
                rtol=1e-10)
    assert bool(out.hit) and float(out.t) == pytest.approx(np.pi / 2, abs=1e-8)


def test_a_pass_that_runs_out_of_steps_says_it_failed():
    out = solve(oscillator, lambda t, y, a: jnp.stack([1.0 + 0.0 * t]), [1.0, 0.0], 100.0, max_steps=20)
    assert bool(out.failed) and not bool(out.hit) and float(out.t) < 100.0


def test_a_buffer_filled_exactly_keeps_its_last_step_and_one_too_small_says_so():
    """A pass that keeps as many steps as its room: its last step's rows are read from that step, not from the
    pass's closing write (no crossing: nothing to keep, and nowhere left to write it).  One place fewer and
    the count runs past the room (the run is taken again with more)."""
    grid = np.linspace(0.0, 3.0, 61)
    never = lambda t, y, a: jnp.stack([1.0 + 0.0 * t])
    whole = solve(oscillator, never, [1.0, 0.0], 3.0, grid=grid, rtol=1e-8)
    steps = int(whole.count)
    exact = solve(oscillator, never, [1.0, 0.0], 3.0, grid=grid, rtol=1e-8, room=steps)
    np.testing.assert_array_equal(exact.grid_state, whole.grid_state)
    np.testing.assert_allclose(exact.grid_state[:-1, 0], np.cos(grid[:-1]), atol=1e-6)
    short = solve(oscillator, never, [1.0, 0.0], 3.0, grid=grid, rtol=1e-8, room=steps - 1)
    assert int(short.count) > steps - 1


@pytest.mark.slow
def test_every_row_is_written_from_the_kept_steps_however_many_a_run_takes():
    """The rows are written after the loop from the steps it kept: Modelica's First takes some 1 000 steps for
    its 2 001 rows.  One run keeps room for a step a padded row: every row up to the end is written, none
    left NaN.  A sweep's chunk keeps room for fewer and is run again with room for them all: its rows are
    written too."""
    from helpers import SCENARIOS

    from hoistsim import simulate, sweep
    from hoistsim.machine.assemble import build_plan, step_room
    from hoistsim.scenario.loading import load_scenario

    scenario = load_scenario(SCENARIOS / "modelica" / "First.yaml")
    run = simulate(scenario)
    assert run.stats["steps"] - run.stats["rejected_steps"] > step_room(build_plan(scenario)[0], sweep=True)
    assert all(np.isfinite(values).all() for values in run.series.values())
    swept = sweep(load_scenario(SCENARIOS / "modelica" / "First.yaml", sweeps=["simulation.rtol=1e-8,1e-9"]))
    for one in swept.runs:
        assert all(np.isfinite(values).all() for values in one.series.values())


def _reads(guard):
    """The guard, and a list that counts how many times the compiled search reads it."""
    calls = []

    def counted(t, y, a):
        jax.debug.callback(lambda: calls.append(1))
        return guard(t, y, a)
    return counted, calls


def test_a_crossing_is_located_in_a_few_reads_of_the_guards_not_fifty_halvings():
    """The search takes the guards' own secant (Illinois): a smooth guard's root to 1e-15 s in a handful of
    reads where halving a step of ~0.3 s to 1e-15 s takes some fifty."""
    guards, calls = _reads(lambda t, y, a: jnp.stack([y[0]]))
    out = solve(oscillator, guards, [1.0, 0.0], 3.0)
    steps = int(out.steps)
    assert float(out.t) == pytest.approx(np.pi / 2, abs=1e-11) and float(out.y[0]) <= 0.0
    located = len(calls) - steps - 1  # the reads at the start and at each step's end aside
    assert 0 < located <= 12, located


def test_a_guard_that_bends_sharply_is_still_located_to_the_last_digits():
    """A guard far from a line across its step (1 - (x / 0.7)^20, flat then plunging): each end moves in
    turn under the Illinois rule, halvings where the secant stalls; the root to 1e-14 all the same."""
    guards, calls = _reads(lambda t, y, a: jnp.stack([1.0 - (y[0] / 0.7) ** 20]))
    out = solve(moving, guards, [0.0], 1.0)
    assert float(out.t) == pytest.approx(0.7, abs=1e-14) and float(1.0 - (out.y[0] / 0.7) ** 20) <= 0.0
    assert len(calls) - int(out.steps) - 1 <= 60


def kinked(t, y, args):
    """x' = 1 up to x = 0.5, then x' = 1 + 40 (x - 0.5): the rate bends at x = 0.5."""
    return jnp.stack([1.0 + 40.0 * jnp.maximum(y[0] - 0.5, 0.0)])


def test_a_step_foretold_to_cross_a_bend_ends_just_past_it_instead_of_being_refused_in_turn():
    """A table's knot ends a pass (a kink guard) where the rate bends: steps across it are refused for the
    bend's error, and the controller shrinks them blindly towards it.  Told which guards are bends, a step the
    guard's last step foretells to cross one stops just short of it, and the next ends just past it: none
    refused; the crossing found is the same."""
    def bend(t, y, a):
        return jnp.stack([0.5 - y[0]])

    blind = solve(kinked, bend, [0.0], 1.0, rtol=1e-10)
    told = SimpleNamespace()

    def go(y0):
        return integrate_pass(diffrax.Tsit5(), None, bend, 0.0, y0, 1.0, rtol=1e-10, atol=1e-12, dtmax=jnp.inf,
                              max_steps=1000, field=kinked, bends=jnp.asarray([True]))
    out = jax.jit(go)(jnp.asarray([0.0]))
    told.t, told.rejected, told.steps = float(out.t), int(out.rejected), int(out.steps)
    # (the crossing's step bends inside: its interpolant, and the root on it, are as good as the tolerance)
    assert told.t == pytest.approx(0.5, abs=1e-9) and float(blind.t) == pytest.approx(0.5, abs=1e-9)
    assert int(blind.rejected) > 10 and told.rejected == 0 and 2 * told.steps < int(blind.steps)


def test_a_pass_goes_on_with_the_step_it_is_given_instead_of_guessing_one():
    """A pass told its first step (the last pass's steps, carried over where nothing jumped) takes it: here one
    step to the end of a field solved exactly; guessed afresh from the rates it starts small and grows."""
    never = lambda t, y, a: jnp.stack([1.0 + 0.0 * t])

    def go(first_step):
        return integrate_pass(diffrax.Tsit5(), None, never, 0.0, jnp.asarray([0.0]), 1.0, rtol=1e-10, atol=1e-12,
                              dtmax=jnp.inf, max_steps=1000, field=moving, first_step=first_step)
    carried, guessed = jax.jit(go)(jnp.asarray(2.0)), jax.jit(go)(jnp.asarray(jnp.nan))
    assert int(carried.steps) == 1 and int(guessed.steps) > 1
    assert float(carried.y[0]) == pytest.approx(1.0, abs=1e-14) and float(guessed.y[0]) == pytest.approx(1.0, abs=1e-14)

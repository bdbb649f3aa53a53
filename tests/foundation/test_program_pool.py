"""The process's compiled programs: the least recently used let go before the kernel's limit, compiled again
when wanted again, with the same answers."""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np
import pytest
from helpers import SHORT, with_force

from hoistsim import _jax, program_hints, program_pool, stored_programs
from hoistsim.program_pool import ProgramPool


def _program(power: int):
    return lambda: jax.jit(lambda x: jnp.sum(x**power))


@pytest.fixture
def pool(monkeypatch):
    """A pool of its own, in place of the process's."""
    fresh = ProgramPool()
    monkeypatch.setattr(_jax, "programs", fresh)
    return fresh


def test_past_the_count_allowed_the_least_recently_used_goes_and_comes_back_the_same(pool, monkeypatch):
    monkeypatch.setenv(program_pool.MAX_PROGRAMS_VARIABLE, "2")
    x = jnp.arange(5.0)
    answers = {}
    for power in (1, 2, 3):
        run = _jax.executable(_program(power), x, name=f"power-{power}")
        answers[power] = float(run(x))
        assert len(pool) <= 2
    assert pool.let_go == 1 and f"{np.sum(np.arange(5.0) ** 3):g}" == f"{answers[3]:g}"
    _jax.executable(_program(2), x, name="power-2")  # held: now the most recently used
    again = _jax.executable(_program(1), x, name="power-1")  # let go before: compiled again, power-3 goes
    assert float(again(x)) == answers[1] == 10.0
    assert pool.let_go == 2
    assert float(_jax.executable(_program(2), x, name="power-2")(x)) == answers[2]
    assert pool.let_go == 2  # power-2 was held all along


def test_programs_are_let_go_before_the_process_reaches_its_memory_maps_limit(pool, monkeypatch):
    """Each program 'takes' 100 maps of a limit of 1000: the pool stays under MAP_SHARE of it."""
    held = [200]
    monkeypatch.setattr(program_pool, "memory_maps", lambda: (held[0], 1000))
    monkeypatch.delenv(program_pool.MAX_PROGRAMS_VARIABLE, raising=False)

    def build(index):
        def make():
            held[0] += 100
            return f"program {index}"
        return make

    real = ProgramPool._let_go_oldest

    def let_go(self):
        real(self)
        held[0] -= 100  # unmapped with the last reference

    monkeypatch.setattr(ProgramPool, "_let_go_oldest", let_go)
    for index in range(12):
        pool.make(f"key-{index}", build(index))
        assert held[0] <= program_pool.MAP_SHARE * 1000 + 100
    assert pool.let_go == 12 - len(pool) and pool.get("key-11") == "program 11" and "key-0" not in pool
    assert len(pool) == 3  # before the next: 200 + 3 x 100 held, and the next one's 100 would reach 600


def test_a_watch_that_meets_more_structures_than_it_may_hold_answers_each_as_the_first_time(tmp_path, monkeypatch):
    from hoistsim.cli.watching import Watch

    monkeypatch.setenv(program_pool.MAX_PROGRAMS_VARIABLE, "1")
    monkeypatch.setattr(_jax, "programs", ProgramPool())
    scenario, output = tmp_path / "scene.yaml", tmp_path / "scene.h5"
    said = []
    watched = Watch(scenario, output=output, echo=said.append)
    for solver in ("tsit5", "dopri5", "tsit5"):
        scenario.write_text(with_force(SHORT, 2600).replace("solver: tsit5", f"solver: {solver}"), encoding="utf-8")
        assert watched.run()
        assert len(_jax.programs) == 1
    assert _jax.programs.let_go == 2
    assert said[0].split(": ", 1)[1].rsplit(" (", 1)[0] == said[2].split(": ", 1)[1].rsplit(" (", 1)[0]


def test_a_program_stored_under_other_xla_flags_is_not_served(pool, monkeypatch, tmp_path):
    """XLA's flags are part of a stored program's key: a process started with other flags builds its own."""
    monkeypatch.setattr(_jax, "_executables", str(tmp_path))
    x = jnp.arange(3.0)
    _jax.executable(_program(2), x, name="square")
    assert len(list(tmp_path.glob("*.bin"))) == 1
    monkeypatch.setenv("XLA_FLAGS", _jax.os.environ.get("XLA_FLAGS", "") + " --xla_cpu_enable_fast_math=false")
    monkeypatch.setattr(_jax, "programs", ProgramPool())
    assert float(_jax.executable(_program(2), x, name="square")(x)) == 5.0
    assert len(list(tmp_path.glob("*.bin"))) == 2  # compiled and stored under its own key


def test_a_program_read_ahead_is_served_as_read_without_reading_or_compiling_it_again(pool, monkeypatch, tmp_path):
    """What `hoistsim run` does where the command ran before: the stored program is read in a thread while
    the scenario is read, and the call that wants it takes it from there."""
    monkeypatch.setattr(_jax, "_executables", str(tmp_path))
    x = jnp.arange(4.0)
    with _jax.serving_recorded() as served:
        first = float(_jax.executable(_program(3), x, name="cube")(x))
    assert len(served) == 1 and len(list(tmp_path.glob("*.bin"))) == 1
    monkeypatch.setattr(_jax, "programs", ProgramPool())
    monkeypatch.setattr(_jax, "read_ahead", stored_programs.ReadAhead())
    _jax.preload(served)

    def never():
        raise AssertionError("read ahead: neither read again nor compiled")

    monkeypatch.setattr(_jax, "read", lambda *args: never())
    assert float(_jax.executable(never, x, name="cube")(x)) == first == 36.0


def test_a_hint_that_no_longer_fits_leaves_the_program_to_be_made_as_usual(pool, monkeypatch, tmp_path):
    monkeypatch.setattr(_jax, "_executables", str(tmp_path))
    monkeypatch.setattr(_jax, "read_ahead", stored_programs.ReadAhead())
    _jax.preload([("0" * 64, 1)])  # no such program stored
    x = jnp.arange(4.0)
    assert float(_jax.executable(_program(2), x, name="square")(x)) == 14.0
    assert _jax.read_ahead.take("0" * 64) == (None, None)  # read, found wanting, and let go


def test_a_command_remembers_the_programs_it_was_served(monkeypatch, tmp_path):
    monkeypatch.setenv("HOISTSIM_CACHE_DIR", str(tmp_path))
    hint = program_hints.command_hint("scenario.yaml", ("motor.inertia=1 kg*m^2",), (), False)
    assert hint != program_hints.command_hint("scenario.yaml", (), (), False)
    assert program_hints.programs_wanted(hint) == []
    program_hints.remember_programs(hint, [("a" * 64, 2)])
    assert program_hints.programs_wanted(hint) == [("a" * 64, 2)]
    (tmp_path / "hints" / f"{hint}.json").write_text("{not json")
    assert program_hints.programs_wanted(hint) == []  # unreadable: as if the command never ran
    monkeypatch.setenv("HOISTSIM_CACHE_DIR", "")
    program_hints.remember_programs(hint, [("a" * 64, 2)])  # the cache off: nothing kept, nothing read
    assert program_hints.programs_wanted(hint) == []


class _Poison:
    """Unpickling it fails loudly: what a structure of arguments naming classes that have changed may do worse."""

    def __reduce__(self):
        return (_explode, ())


def _explode():
    raise AssertionError("a stored program of other code was unpickled past its origin")


def test_a_stored_program_of_other_code_is_not_read_past_its_origin(tmp_path):
    """A command read ahead the programs it ran before an edit or an upgrade: such a program's origin is another,
    and nothing more of it is unpickled (its arguments' structure may name element classes whose fields have
    since changed: a crash in XLA's tree code, not an error); the program is compiled again where it is
    wanted.  A program stored before origins were kept (three parts) is stale alike."""
    import pickle

    from hoistsim import stored_programs

    other = tmp_path / "other.bin"
    other.write_bytes(pickle.dumps((("another source",) + stored_programs.origin()[1:], b"xla",
                                    pickle.dumps(_Poison()), pickle.dumps(_Poison()))))
    older = tmp_path / "older.bin"
    older.write_bytes(pickle.dumps((b"xla", pickle.dumps(_Poison()), pickle.dumps(_Poison()))))
    for path in (other, older):
        with pytest.raises(stored_programs.StaleProgram):
            stored_programs.read(str(path), 1)
        assert stored_programs.ReadAhead._read(str(path), 1) == (None, None)

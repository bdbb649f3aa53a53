"""The command line imports what a command needs, and every array hoistsim makes is float64 all the same."""

from __future__ import annotations

import ast
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import EXERCISE6_FILE, ROOT

PACKAGE = ROOT / "hoistsim"
# Subpackages whose __init__ imports hoistsim._jax (elements import the core first).
GUARDED_PACKAGES = ("machine/core", "machine/elements", "results/periodic")

PROBE = """
import json, os, sys
sys.argv = ["hoistsim", *{args!r}]

def report(status):
    print(json.dumps({{"status": status, "loaded": sorted(m for m in {watched!r} if m in sys.modules)}}), file=sys.stderr)

exit_now = os._exit
os._exit = lambda status: (report(status), sys.stderr.flush(), exit_now(status))  # a command done early
from hoistsim.cli import main
status = 0
try:
    main()
except SystemExit as exit:
    status = exit.code
report(status)
"""
HEAVY = ["jax", "diffrax", "matplotlib", "dask", "distributed", "xarray", "scipy.optimize", "pint"]


def _loaded(args, cwd) -> tuple[int, list[str]]:
    """(exit status, which of HEAVY a fresh process running ``hoistsim ARGS`` imported)."""
    program = PROBE.format(args=[str(a) for a in args], watched=HEAVY)
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, cwd=cwd)
    report = json.loads(done.stderr.strip().splitlines()[-1])
    return report["status"], report["loaded"]


def _imports_jax(path: Path) -> bool:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    for node in tree.body:  # the module's own imports; those inside functions run after the package's
        if isinstance(node, ast.Import) and any(a.name.split(".")[0] == "jax" for a in node.names):
            return True
        if isinstance(node, ast.ImportFrom) and node.level == 0 and (node.module or "").split(".")[0] == "jax":
            return True
    return False


def _imports_float64_set_up(path: Path) -> bool:
    text = path.read_text(encoding="utf-8")
    return any(mark in text for mark in ("import _jax", "._pytree import", "from .core", "from ..core", "machine.core"))


def test_every_module_that_uses_jax_sets_float64_first():
    """hoistsim/__init__ no longer imports JAX (a `check` needs none): each module that does sees to float64."""
    for package in GUARDED_PACKAGES:
        assert _imports_float64_set_up(PACKAGE / package / "__init__.py") or package == "machine/elements"
    assert "from ..core" in (PACKAGE / "machine" / "elements" / "__init__.py").read_text(encoding="utf-8")
    unguarded = [str(p.relative_to(PACKAGE)) for p in sorted(PACKAGE.rglob("*.py"))
                 if _imports_jax(p) and str(p.relative_to(PACKAGE).parent.as_posix()) not in GUARDED_PACKAGES
                 and p.name != "_jax.py" and not _imports_float64_set_up(p)]
    assert unguarded == []


def test_importing_a_module_of_the_core_alone_gives_float64():
    program = ("import hoistsim.machine.core.bodies, jax, jax.numpy as jnp; "
               "print(jnp.zeros(1).dtype, 'jax' in __import__('sys').modules)")
    done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, cwd=ROOT, check=True)
    assert done.stdout.split() == ["float64", "True"]


def test_help_and_compare_import_no_jax_and_check_no_solver_library(tmp_path, monkeypatch):
    """`check` prints the reduced model worked out by the machine's own elements (JAX code), but never
    the solver library, figures or the cluster; pint only where a unit is new to the cache folder."""
    monkeypatch.setenv("HOISTSIM_CACHE_DIR", str(tmp_path / "cache"))
    assert _loaded(["--help"], tmp_path) == (0, [])
    status, loaded = _loaded(["compare", tmp_path / "absent.h5"], tmp_path)
    assert status == 2 and loaded == []
    status, loaded = _loaded(["check", EXERCISE6_FILE], tmp_path)
    assert status == 0 and loaded == ["jax", "pint"]
    status, loaded = _loaded(["check", EXERCISE6_FILE], tmp_path)  # every unit of it read before
    assert status == 0 and loaded == ["jax"]


def test_units_read_before_are_read_without_pint_and_to_the_same_bits(tmp_path):
    """The factors kept on disk are pint's own: a scenario read again in a new process gives the same
    numbers to the bit; a factors file that cannot be read is read again by pint."""
    program = ("import json, sys; from hoistsim.scenario.loading import load_scenario; "
               f"s = load_scenario({str(EXERCISE6_FILE)!r}, overrides=['clutch.engagement_force=3.3 kN']); "
               "print(json.dumps([s.resolved(), 'pint' in sys.modules]))")
    env = dict(os.environ, HOISTSIM_CACHE_DIR=str(tmp_path / "cache"))

    def read():
        done = subprocess.run([sys.executable, "-c", program], capture_output=True, text=True, cwd=ROOT, env=env,
                              check=True)
        return json.loads(done.stdout)

    first, again = read(), read()
    assert first[1] and not again[1] and first[0] == again[0]
    assert again[0]["clutch"]["engagement_force"]["forces"] == [3300.0]
    (stored,) = (tmp_path / "cache" / "units").glob("factors-*.json")
    stored.write_text("{not json", encoding="utf-8")
    broken = read()
    assert broken[1] and broken[0] == first[0]


@pytest.mark.slow
def test_a_warm_run_loads_its_program_and_imports_no_figures_no_cluster_no_solver_library(tmp_path, monkeypatch):
    """The second run of a scene loads the stored program: it never traces, so the solver library stays out."""
    monkeypatch.setenv("HOISTSIM_CACHE_DIR", str(tmp_path / "cache"))
    args = ["run", EXERCISE6_FILE, "-o", tmp_path / "out.h5", "--set", "simulation.duration=0.2 s"]
    status, first = _loaded(args, tmp_path)
    assert status == 0 and "diffrax" in first  # the first compiled it
    status, warm = _loaded(args, tmp_path)
    assert status == 0
    assert warm == ["jax"]  # its units too were read before

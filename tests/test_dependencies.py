"""What the tests import is declared: a dependency of the package or of its `test` extra (the suite runs
after `pip install -e ".[test]"` alone), or skipped where absent (`pytest.importorskip`: Dask's extra)."""

from __future__ import annotations

import ast
import re
import sys
import tomllib
from importlib.metadata import packages_distributions

from helpers import ROOT

TESTS = ROOT / "tests"


def _distribution(requirement: str) -> str:
    """A requirement's distribution name, normalised (PEP 503): "ruamel.yaml>=0.18" -> "ruamel-yaml"."""
    return re.sub(r"[-_.]+", "-", re.match(r"[A-Za-z0-9._-]+", requirement).group()).lower()


def _declared() -> set[str]:
    project = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]
    return {_distribution(r) for r in project["dependencies"] + project["optional-dependencies"]["test"]}


def _imported() -> dict[str, set[str]]:
    """The third-party modules the tests import (inside functions too), each with the files importing it;
    a module a file skips without (`pytest.importorskip`) does not count there."""
    ours = {path.stem for path in TESTS.rglob("*.py")} | {"hoistsim"}
    found: dict[str, set[str]] = {}
    for path in sorted(TESTS.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        skipped = {node.args[0].value for node in ast.walk(tree)
                   if isinstance(node, ast.Call) and getattr(node.func, "attr", "") == "importorskip"
                   and node.args and isinstance(node.args[0], ast.Constant)}
        for node in ast.walk(tree):
            names = ([alias.name for alias in node.names] if isinstance(node, ast.Import) else
                     [node.module] if isinstance(node, ast.ImportFrom) and not node.level else [])
            for top in {name.split(".")[0] for name in names}:
                if top not in sys.stdlib_module_names and top not in ours and top not in skipped:
                    found.setdefault(top, set()).add(str(path.relative_to(TESTS)))
    return found


def test_every_module_the_tests_import_is_declared():
    declared, providers = _declared(), packages_distributions()
    missing = [f"{module} ({', '.join(providers.get(module, ['not installed']))}), imported by "
               f"{', '.join(sorted(files))}" for module, files in sorted(_imported().items())
               if not declared & {_distribution(d) for d in providers.get(module, [])}]
    assert not missing, "declare in pyproject.toml's test extra, or importorskip:\n" + "\n".join(missing)

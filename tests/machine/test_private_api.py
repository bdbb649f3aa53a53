"""The private API of JAX, jaxlib, diffrax and equinox that hoistsim uses is reached from one module, and an
upgrade that moves a name of it fails here, naming the package, its version and the name."""

from __future__ import annotations

import ast
import importlib
import re
from importlib.metadata import version
from pathlib import Path

import pytest

import hoistsim

PACKAGE = Path(hoistsim.__file__).parent
THIRD_PARTY = ("jax", "jaxlib", "diffrax", "equinox", "optimistix", "lineax")
# the one module that may reach for them
PRIVATE_API = PACKAGE / "machine" / "core" / "private_api.py"


def test_every_private_name_is_where_hoistsim_reaches_for_it():
    try:
        from hoistsim.machine.core import private_api
    except ImportError as exc:  # reach() names the package, its version and the name that moved
        pytest.fail(str(exc))
    assert private_api.REACHED
    for package, module, name in private_api.REACHED:
        assert module.split(".")[0] == package
        assert getattr(private_api, name) is getattr(importlib.import_module(module), name), (package, module, name)


@pytest.mark.parametrize("package, module, name", [
    ("equinox", "equinox.internal", "no_such_loop"),  # a name gone from its module
    ("diffrax", "diffrax._no_such_module", "use_stepsize_tol"),  # a module gone
])
def test_a_moved_name_says_which_package_version_and_name(package, module, name):
    from hoistsim.machine.core.private_api import reach

    message = rf"^{package} {re.escape(version(package))} has no {re.escape(module)}\.{name}, which hoistsim uses"
    with pytest.raises(ImportError, match=message):
        reach(package, module, name)


def _private(dotted: str) -> bool:
    """A module path or attribute chain of a third-party package that is not its public API."""
    parts = dotted.split(".")
    return parts[0] in THIRD_PARTY and (parts[0] == "jaxlib" or parts[:2] == ["equinox", "internal"] or any(
        p.startswith("_") and not p.endswith("__") for p in parts[1:]))


def _dotted(node) -> str | None:
    """``a.b.c`` of an attribute chain on a name, else None."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    return ".".join([node.id, *reversed(parts)]) if isinstance(node, ast.Name) else None


def test_no_other_module_uses_a_private_name_of_jax_diffrax_or_equinox():
    found = []
    for path in sorted(PACKAGE.rglob("*.py")):
        if path == PRIVATE_API:
            continue
        tree = ast.parse(path.read_text())
        where = path.relative_to(PACKAGE)
        modules = {}  # a local name -> the module or name it was imported as
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    local = alias.asname or alias.name.split(".")[0]
                    modules[local] = alias.name if alias.asname else local
                    found += [f"{where}:{node.lineno} imports {alias.name}"] if _private(alias.name) else []
            elif isinstance(node, ast.ImportFrom) and not node.level and node.module:
                for alias in node.names:
                    modules[alias.asname or alias.name] = full = f"{node.module}.{alias.name}"
                    found += [f"{where}:{node.lineno} imports {full}"] if _private(full) else []
        for node in ast.walk(tree):  # attributes: ``jax._src.core``, ``eqx.internal.while_loop``
            dotted = _dotted(node) if isinstance(node, ast.Attribute) else None
            if dotted is None or dotted.split(".")[0] not in modules:
                continue
            first, *rest = dotted.split(".")
            if _private(".".join([modules[first], *rest])) and not _private(modules[first]):
                found.append(f"{where}:{node.lineno} uses {'.'.join([modules[first], *rest])}")
    assert not found, "reach for these through hoistsim/machine/core/private_api.py:\n" + "\n".join(sorted(set(found)))

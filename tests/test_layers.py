"""The package's layers: no import circle, and no module imports from a layer above its own.

Every import counts, those inside functions too (a lazy import is still a dependency).  The
order is written here once, lowest first; a module may import from its own layer and any below.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import hoistsim

PACKAGE = Path(hoistsim.__file__).parent

# lowest first; each entry is a module or a folder of hoistsim
LAYERS = (
    ("foundation", ("errors", "cache_folders", "program_pool", "program_origin", "stored_programs", "program_hints",
                    "_jax", "_pytree", "switch_kinds", "__init__")),
    ("components", ("components",)),
    ("display", ("display",)),
    ("scenario", ("scenario",)),
    ("machine", ("machine",)),
    ("results", ("results",)),
    ("running", ("running",)),
    ("figures", ("figures",)),
    ("references", ("references",)),
    ("studies", ("studies",)),
    ("command line", ("cli",)),
)


def _modules() -> dict[str, tuple[Path, bool]]:
    """hoistsim's modules by dotted name: (file, is a package)."""
    found = {}
    for path in PACKAGE.rglob("*.py"):
        parts = ("hoistsim",) + path.relative_to(PACKAGE).with_suffix("").parts
        is_package = parts[-1] == "__init__"
        found[".".join(parts[:-1] if is_package else parts)] = (path, is_package)
    return found


def _imports(name: str, path: Path, is_package: bool, modules) -> set[str]:
    """The hoistsim modules ``name`` imports, anywhere in its file."""
    package = name if is_package else name.rsplit(".", 1)[0]
    found = set()
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.Import):
            found.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                base = ".".join(parts[: len(parts) - node.level + 1] + ([base] if base else []))
            for alias in node.names:  # `from . import tables` imports the module hoistsim.scenario.tables
                found.add(f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base)
    return {m for m in found if m in modules and m != name}


def _graph() -> dict[str, set[str]]:
    modules = _modules()
    return {name: _imports(name, path, is_package, modules) for name, (path, is_package) in modules.items()}


def layer_of(module: str) -> int:
    first = module.split(".")[1] if "." in module else "__init__"
    for rank, (_, members) in enumerate(LAYERS):
        if first in members:
            return rank
    raise AssertionError(f"{module} belongs to no layer: add its folder to LAYERS in {__file__}")


def circles(graph) -> list[list[str]]:
    """The import graph's strongly connected groups of more than one module (Tarjan's algorithm)."""
    index, low, stack, on_stack, groups = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            group = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                group.append(w)
                if w == v:
                    break
            if len(group) > 1:
                groups.append(sorted(group))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return groups


def test_every_module_has_a_layer():
    for module in _graph():
        layer_of(module)


def test_no_import_runs_up_a_layer():
    upward = [f"{a} ({LAYERS[layer_of(a)][0]}) imports {b} ({LAYERS[layer_of(b)][0]})"
              for a, targets in sorted(_graph().items()) for b in sorted(targets)
              if layer_of(b) > layer_of(a) and a != "hoistsim"]
    assert not upward, "\n".join(upward)


def test_no_import_circles():
    assert not circles(_graph())


def test_no_module_above_400_lines():
    long = {name: n for name, (path, _) in _modules().items() if (n := len(path.read_text().splitlines())) > 400}
    assert not long, long


# Each module of the figures, after the results' reading: the first after whose import JAX is loaded is printed.
FIRST_TO_LOAD_JAX = """
import importlib, pkgutil, sys
import hoistsim.figures
names = ["hoistsim.results.reading"]
names += [f"hoistsim.figures.{m.name}" for m in pkgutil.iter_modules(hoistsim.figures.__path__)]
for name in names:
    importlib.import_module(name)
    if "jax" in sys.modules:
        print(name)
        break
"""


def test_reading_and_drawing_a_results_file_import_no_jax():
    """`hoistsim plot OUT.h5` needs no machine: the results' reading and every module of the figures, imported in a
    fresh process, leave JAX out of it."""
    done = subprocess.run([sys.executable, "-c", FIRST_TO_LOAD_JAX], capture_output=True, text=True, check=True,
                          cwd=PACKAGE.parent)  # the hoistsim under test first on the path
    assert done.stdout == "", f"importing {done.stdout.strip()} loads jax"


def test_the_scenario_the_components_and_the_displays_import_no_jax():
    """Reading and checking a scenario never needs JAX (`hoistsim check` loads it only for the reduced model),
    nor does knowing what a part shows in the figures."""
    found = []
    for folder in ("scenario", "components", "display"):
        for path in sorted((PACKAGE / folder).rglob("*.py")):
            for node in ast.walk(ast.parse(path.read_text())):
                names = ([a.name for a in node.names] if isinstance(node, ast.Import) else
                         [node.module or ""] if isinstance(node, ast.ImportFrom) and not node.level else [])
                found += [f"{path.relative_to(PACKAGE)} imports {n}" for n in names if n.split(".")[0] in
                          ("jax", "jaxlib", "diffrax", "equinox")]
    assert not found, found


def test_the_figures_read_results_and_displays_only():
    """A figure is drawn from a results file (or runs in memory as reading gives them) and the parts' displays:
    it never needs the machine, a run or the scenario's schema."""
    allowed = {layer_of("hoistsim.errors"), layer_of("hoistsim.display"), layer_of("hoistsim.results"),
               layer_of("hoistsim.figures")}
    found = [f"{a} imports {b}" for a, targets in sorted(_graph().items()) if a.startswith("hoistsim.figures")
             for b in sorted(targets) if layer_of(b) not in allowed]
    assert not found, "\n".join(found)


def test_the_core_accepts_the_solvers_the_schema_names():
    """The core does not import the scenario's schema: its table of solvers is its own, the same names."""
    from hoistsim.machine.core.loop import SOLVERS
    from hoistsim.scenario.schema import SOLVERS as SOLVER_NAMES

    assert tuple(SOLVERS) == SOLVER_NAMES


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def test_no_private_name_imported_across_modules():
    """A name with a leading underscore is its module's own: no other module imports it (``from .loop import
    _run``) or reads it off the module (``loop._run``).  hoistsim's private modules (``_jax``, ``_pytree``)
    are modules, not names: importing them is fine, their own private names are not."""
    modules = _modules()
    found = []
    for name, (path, is_package) in sorted(modules.items()):
        package = name if is_package else name.rsplit(".", 1)[0]
        tree = ast.parse(path.read_text())
        bound = {}  # a local name -> the hoistsim module it stands for
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name.split(".")[0] == "hoistsim":
                        bound[alias.asname or "hoistsim"] = alias.name if alias.asname else "hoistsim"
            elif isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    parts = package.split(".")
                    base = ".".join(parts[: len(parts) - node.level + 1] + ([base] if base else []))
                if base not in modules:
                    continue
                for alias in node.names:
                    if f"{base}.{alias.name}" in modules:
                        bound[alias.asname or alias.name] = f"{base}.{alias.name}"
                    elif _private(alias.name) and base != name:
                        found.append(f"{name}:{node.lineno} imports {alias.name} from {base}")
        for node in ast.walk(tree):
            if not isinstance(node, ast.Attribute):
                continue
            chain, value = [node.attr], node.value
            while isinstance(value, ast.Attribute):
                chain.append(value.attr)
                value = value.value
            if not isinstance(value, ast.Name) or value.id not in bound:
                continue
            module, *rest = [bound[value.id], *reversed(chain)]
            while len(rest) > 1 and f"{module}.{rest[0]}" in modules:  # hoistsim.machine.core.loop._run
                module, rest = f"{module}.{rest[0]}", rest[1:]
            if len(rest) == 1 and _private(rest[0]) and module != name:
                found.append(f"{name}:{node.lineno} reads {module}.{rest[0]}")
    assert not found, "\n".join(found)

"""No import cycle among the Python modules of the source tree (the package root in python/, each
component's python/ folder: talus.dem, talus.flow, talus.coupling, talus.fem and the drop-in
packages yade, yade_femxdem, yadeimport).

The graph is read from the sources with ``ast``, without importing anything, so it holds for a
build without some components too. Every import statement counts, at module level or inside a
function (a deferred import is still a dependency, only a later one), except under
``if TYPE_CHECKING:``, which never runs. ``from talus.dem import O`` depends on the package
``talus.dem`` (its ``__init__``), ``from talus.dem.core import clumps`` on the module
``talus.dem.core.clumps``. The parent packages Python imports before a module are not counted: a
package's ``__init__`` may import its own modules, its modules may not import it back.
"""
import ast
import re
from collections import deque
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
ROOTS = [REPO / "python", *(REPO / component / "python" for component in ("dem", "flow", "coupling", "fem"))]


def source_modules(roots: list[Path]) -> dict[str, Path]:
    """Dotted module name -> file, for every .py under the roots (a package is its __init__)."""
    modules = {}
    for root in roots:
        for path in sorted(root.rglob("*.py")):
            parts = list(path.relative_to(root).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            name = ".".join(parts)
            assert name not in modules, f"module {name} is in both {modules.get(name)} and {path}"
            modules[name] = path
    return modules


def built_modules(repo: Path) -> set[str]:
    """The package's modules that are not Python sources: the compiled ones (talus_python_module
    in CMake) and the generated build table."""
    names = {"talus._build_config"}
    for cmake in repo.glob("*/CMakeLists.txt"):
        names.update(f"talus.{name}" for name in re.findall(r"talus_python_module\((\w+)", cmake.read_text()))
    return names


def _imports(node: ast.AST):
    """Import statements that run, skipping the body of `if TYPE_CHECKING:`."""
    skipped = isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test)
    for child in node.orelse if skipped else ast.iter_child_nodes(node):
        if isinstance(child, (ast.Import, ast.ImportFrom)):
            yield child
        else:
            yield from _imports(child)


def import_graph(modules: dict[str, Path], leaves: set[str], base: Path = REPO) -> dict[str, dict[str, str]]:
    """module -> {imported module of the source tree: "file:line" (from base) of its first import}."""
    def owner(name: str) -> str | None:
        """The source module that `name` is or is defined in; None outside the source tree."""
        while name and name not in modules:
            if name in leaves:
                return None
            name = name.rpartition(".")[0]
        return name or None

    graph = {}
    for module, path in modules.items():
        package = module if path.name == "__init__.py" else module.rpartition(".")[0]
        edges = graph[module] = {}
        for node in _imports(ast.parse(path.read_text(), str(path))):
            if isinstance(node, ast.Import):
                targets = [owner(alias.name) for alias in node.names]
            else:
                origin = node.module or ""
                if node.level:
                    anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
                    origin = ".".join(anchor + ([node.module] if node.module else []))
                targets = [owner(f"{origin}.{alias.name}") for alias in node.names]
            for target in targets:
                if target is not None and target != module:
                    edges.setdefault(target, f"{path.relative_to(base)}:{node.lineno}")
    return graph


def cycles(graph: dict[str, dict[str, str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan), largest first."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []

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
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for v in graph:
        if v not in index:
            visit(v)
    return sorted(found, key=len, reverse=True)


def shortest_loop(graph: dict[str, dict[str, str]], component: list[str]) -> list[str]:
    """One shortest import loop through the component's first module, each step with where it is
    written: ["a -> b (a.py:3)", "b -> a (b.py:7)"]."""
    start, inside = component[0], set(component)
    previous, queue = {}, deque([start])
    while queue:
        v = queue.popleft()
        for w in graph[v]:
            if w in inside and w not in previous:
                previous[w] = v
                if w == start:
                    queue.clear()
                    break
                queue.append(w)
    steps, w = [], start
    while True:
        v = previous[w]
        steps.append(f"{v} -> {w} ({graph[v][w]})")
        w = v
        if w == start:
            return steps[::-1]


def describe(graph, found) -> str:
    return "\n".join(f"a cycle of {len(c)} modules ({', '.join(c)}), for instance:\n    "
                     + "\n    ".join(shortest_loop(graph, c)) for c in found)


def test_no_import_cycle():
    modules = source_modules(ROOTS)
    assert "talus" in modules and "talus.dem.core.bodies" in modules and "yade" in modules
    graph = import_graph(modules, built_modules(REPO))
    found = cycles(graph)
    assert not found, "import cycles among the Python modules:\n" + describe(graph, found)


def test_a_made_cycle_is_found_and_named(tmp_path):
    """The check itself, on a package with two cycles: two modules importing each other (one at
    module level, one inside a function), and a module importing its own package back; an import
    under TYPE_CHECKING makes none."""
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "__init__.py").write_text("from pkg import a, d\n")
    (package / "a.py").write_text("from pkg.b import helper\n")
    (package / "b.py").write_text("def helper():\n    from pkg import a\n")
    (package / "c.py").write_text("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    from pkg import a\n")
    (package / "d.py").write_text("def scene():\n    from pkg import DEFAULT\n")
    graph = import_graph(source_modules([tmp_path]), set(), tmp_path)
    found = cycles(graph)
    assert sorted(found) == [["pkg", "pkg.d"], ["pkg.a", "pkg.b"]]
    assert graph["pkg.c"] == {}
    named = describe(graph, found)
    assert "pkg.a -> pkg.b (" in named and "b.py:2)" in named and "pkg.d -> pkg (" in named

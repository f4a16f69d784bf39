"""The import graph of rotorcad, hob and exports: no cycle, no upward import (issue 25).

The graph is read from the source with :mod:`ast`, not from what an import happens to load: every
``import`` and ``from ... import`` statement of a module, at module level and inside functions (the
lazy imports that keep ``import rotorcad`` light are dependencies too). Reference: the layers
ARCHITECTURE.md declares ("Packages and the imports they may make"): the core never imports
``hob``, ``exports`` or ``rotorcad.cli``; ``hob`` and ``exports`` never import ``rotorcad.cli``.
"""

from __future__ import annotations

import ast
import functools
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PACKAGES = ("rotorcad", "hob", "exports")

LAYERS = {  # layer -> the layers it may import (its own included)
    "core": {"core"},
    "hob": {"core", "hob"},
    "exports": {"core", "exports"},
    "cli": {"core", "hob", "exports", "cli"},
}
"""ARCHITECTURE.md's table: ``rotorcad`` (the core), ``hob`` and ``exports`` beside it, the command
line ``rotorcad.cli`` on top."""


def layer(module: str) -> str:
    """Return the layer of a module of the three packages."""
    if module == "rotorcad.cli" or module.startswith("rotorcad.cli."):
        return "cli"
    return module.split(".")[0] if module.split(".")[0] in ("hob", "exports") else "core"


def modules() -> dict[str, Path]:
    """Return every module of the three packages by dotted name (a package by its ``__init__``)."""
    found = {}
    for package in PACKAGES:
        for path in sorted((ROOT / package).rglob("*.py")):
            parts = path.relative_to(ROOT).with_suffix("").parts
            found[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return found


def type_checking_imports(tree: ast.Module) -> set[int]:
    """Return the ids of the import statements under ``if TYPE_CHECKING:`` (read by type checkers
    only, never run, so no dependency at run time)."""
    guarded = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            guarded.update(id(n) for stmt in node.body for n in ast.walk(stmt))
    return guarded


def imports(name: str, path: Path, known: set[str], typing: bool = True) -> set[str]:
    """Return the modules of the three packages that ``name`` (at ``path``) imports, anywhere in it
    (``typing=False``: leaving out the imports under ``if TYPE_CHECKING:``).

    ``from a.b import c`` is an import of ``a.b.c`` when that is a module, else of ``a.b``; a
    relative import is resolved against the module's package. The parents a dotted import loads on
    the way are not counted (they are not what the module uses).
    """
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found = set()
    tree = ast.parse(path.read_text(), str(path))
    skipped = set() if typing else type_checking_imports(tree)
    for node in ast.walk(tree):
        if id(node) in skipped:
            continue
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[: len(package.split(".")) - node.level + 1]
                base = ".".join([*anchor, base] if base else anchor)
            targets = [f"{base}.{alias.name}" if f"{base}.{alias.name}" in known else base for alias in node.names]
        else:
            continue
        found.update(t for t in targets if t.split(".")[0] in PACKAGES)
    return found - {name}


@functools.cache
def graph(typing: bool = True) -> dict[str, set[str]]:
    """Return the import graph: module -> the modules of the three packages it imports
    (``typing=False``: the graph at run time, without the imports for type checkers only)."""
    found = modules()
    known = set(found)
    return {name: imports(name, path, known, typing) for name, path in found.items()}


def test_the_graph_is_read():
    """The reader finds what is known to be there, so that the asserts below cannot pass empty: the
    command line imports the core, hob's verdict the core's sweep plan, a function-level import of
    the core's reading is seen."""
    g = graph()
    assert "rotorcad.design.rotors" in g["rotorcad.cli.rotor"]
    assert "rotorcad.sweep.plan" in g["hob.sweep_check"]
    assert "rotorcad.design.reading" in g["rotorcad.design.files"]  # imported inside load_toml
    assert len(g) > 80


def test_no_upward_import():
    """No module imports a layer above its own (ARCHITECTURE.md)."""
    g = graph()
    upward = sorted(f"{a} -> {b}" for a, targets in g.items() for b in targets if layer(b) not in LAYERS[layer(a)])
    assert not upward, "upward imports:\n" + "\n".join(upward)


def named_modules(path: Path, known: set[str]) -> set[str]:
    """Return the modules of the three packages a module names in a string of its own (a table for
    :func:`importlib.import_module`, as ``rotorcad._ENTRY`` was): an import that ``ast`` does not see
    as one."""
    return {
        node.value for node in ast.walk(ast.parse(path.read_text())) if isinstance(node, ast.Constant) and node.value in known
    }


def test_no_upward_import_by_name():
    """No module names a module above its own layer for a dynamic import (the core's one upward arrow,
    the public ``rotorcad.sweep`` forwarding to ``rotorcad.cli.sweep_run``, was such a name)."""
    found = modules()
    known = set(found)
    upward = sorted(
        f"{name} names {target}"
        for name, path in found.items()
        for target in named_modules(path, known)
        if layer(target) not in LAYERS[layer(name)]
    )
    assert not upward, "upward imports by name:\n" + "\n".join(upward)


def find_cycles(g: dict[str, set[str]]) -> list[list[str]]:
    """Return the strongly connected components of more than one module (Tarjan), each sorted."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []

    def enter(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)

    for root in sorted(g):
        if root in index:
            continue
        enter(root)
        work = [(root, iter(sorted(g.get(root, ()))))]  # iterative: a deep chain cannot overflow the recursion
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    enter(child)
                    work.append((child, iter(sorted(g.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    cycles.append(sorted(component))
    return cycles


def test_no_import_cycle():
    """No module reaches itself through the imports that run (an import under ``if TYPE_CHECKING:``,
    for a type annotation only, does not run; the upward check above counts those too)."""
    cycles = find_cycles(graph(typing=False))
    assert not cycles, "import cycles:\n" + "\n".join(" <-> ".join(c) for c in cycles)


def test_a_cycle_and_an_upward_import_are_found():
    """The checks see what they look for: made-up graphs with a cycle (the one this issue removed,
    rotorcad.design -> rotorcad.cli.common -> rotorcad.design, and a longer one beside a chain),
    and a core module importing the command line."""
    assert find_cycles({"rotorcad.design": {"rotorcad.cli.common"}, "rotorcad.cli.common": {"rotorcad.design"}}) == [
        ["rotorcad.cli.common", "rotorcad.design"]
    ]
    assert find_cycles({"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set()}) == [["a", "b", "c"]]
    assert find_cycles({"a": {"b"}, "b": {"c"}, "c": set()}) == []
    assert "rotorcad.cli.sweep_run" in named_modules(ROOT / "tests" / "test_architecture.py", set(modules()))
    assert layer("rotorcad.cli.common") not in LAYERS[layer("rotorcad.design")]
    assert layer("hob.verdict") in LAYERS[layer("rotorcad.cli.hob_cmd")]
    assert layer("rotorcad.cli.common") not in LAYERS[layer("exports.dxf")]
    guarded = ast.parse("from typing import TYPE_CHECKING\nif TYPE_CHECKING:\n    import rotorcad.gears\nimport hob\n")
    assert len(type_checking_imports(guarded)) >= 2  # the import and its alias, not `import hob`


MODULE_LINES = 800
"""The longest module a newcomer should have to read whole (issue "A core a newcomer can change")."""

CLI_FUNCTION_LINES = 80
"""The longest function of the command line, counted by ``ast`` from ``def`` to its end (decorators
not counted); its cyclomatic complexity is held to 20 by ruff (``[tool.ruff.lint.mccabe]``)."""


def test_no_module_is_longer_than_a_newcomer_reads():
    long = sorted(
        f"{path.relative_to(ROOT)}: {n} lines"
        for path in modules().values()
        if (n := len(path.read_text().splitlines())) > MODULE_LINES
    )
    assert not long, "modules over 800 lines:\n" + "\n".join(long)


def test_no_command_line_function_is_longer_than_80_lines():
    long = []
    for path in sorted((ROOT / "rotorcad" / "cli").glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if (
                isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef)
                and node.end_lineno - node.lineno + 1 > CLI_FUNCTION_LINES
            ):
                long.append(f"{path.name}::{node.name}: {node.end_lineno - node.lineno + 1} lines")
    assert not long, "command-line functions over 80 lines:\n" + "\n".join(long)

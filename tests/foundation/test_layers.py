"""The package's folders are its layers, and imports only point down.

A newcomer reads the pipeline from the folder list: input (``io``), the model, the dialects,
mechanics and views, lint, transforms and reporters, simulation, commands, the CLI. These tests
read every module's imports (no module is run) and hold that shape, and that no modules import
each other in a circle, whether the import is at module level, inside a function, or under
``if TYPE_CHECKING`` (see :func:`dependencies` for why all three count).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "txtool"

# Lower numbers are lower layers; a module may import its own layer or any below it.
LAYERS = {
    "io": 0,
    "model": 1,
    "dialects": 2,
    "mechanics": 3,
    "views": 3,
    "lint": 4,
    "rules": 4,
    "transform": 5,
    "reporters": 5,
    "simulation": 6,
    "commands": 7,
    "cli": 8,
    "__main__": 8,
    "__init__": 8,
}


def module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def layer_of(module: str) -> int:
    parts = module.split(".")
    if len(parts) == 1:  # the package itself: __version__ only
        return LAYERS["__init__"]
    return LAYERS[parts[1]]


def imports(path: Path, root: Path = PACKAGE.parent) -> tuple[set[str], set[str], set[str]]:
    """(module-level imports, type-checking imports, imports in functions) of txtool modules
    (found under ``root``, the folder holding the package)."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    top_nodes = {id(node) for node in _module_level(tree.body)}
    # ``if TYPE_CHECKING:`` imports never run: they count for layers, not for circles.
    typing_only = {
        id(inner)
        for node in tree.body
        if isinstance(node, ast.If) and ast.unparse(node.test) == "TYPE_CHECKING"
        for inner in ast.walk(node)
    }
    top: set[str] = set()
    typing: set[str] = set()
    inner: set[str] = set()
    for node in ast.walk(tree):
        names: list[str] = []
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("txtool"):
            # "from txtool.pkg import submodule" imports the submodule
            names = [f"{node.module}.{alias.name}" for alias in node.names]
        elif isinstance(node, ast.Import):
            names = [a.name for a in node.names if a.name.startswith("txtool")]
        where = top if id(node) in top_nodes else inner
        (typing if id(node) in typing_only else where).update(_existing(n, root) for n in names)
    return top, typing, inner


def _module_level(body: list[ast.stmt]):
    for node in body:
        yield node
        if isinstance(node, (ast.If, ast.Try)):  # if TYPE_CHECKING, try/except ImportError
            yield from _module_level(node.body)
            for handler in getattr(node, "handlers", []):
                yield from _module_level(handler.body)
            yield from _module_level(node.orelse)


def _existing(name: str, root: Path) -> str:
    """``txtool.x.y`` where y may be a name inside module x: the module that exists."""
    while name.count(".") > 0:
        as_path = root / name.replace(".", "/")
        if as_path.with_suffix(".py").exists() or (as_path / "__init__.py").exists():
            return name
        name = name.rsplit(".", 1)[0]
    return name


def graph() -> dict[str, tuple[set[str], set[str], set[str]]]:
    return {module_name(p): imports(p) for p in sorted(PACKAGE.rglob("*.py"))}


def test_no_module_lies_flat_at_the_top_of_the_package():
    flat = sorted(p.name for p in PACKAGE.glob("*.py"))
    assert flat == ["__init__.py", "__main__.py", "cli.py"]


def test_every_folder_is_a_known_layer():
    folders = {p.name for p in PACKAGE.iterdir() if p.is_dir() and p.name != "__pycache__"}
    assert folders <= set(LAYERS), folders - set(LAYERS)


@pytest.mark.parametrize("kind", ["module-level", "inside functions"])
def test_imports_only_point_down(kind):
    upward = []
    for module, (top, typing, inner) in graph().items():
        for target in top | typing if kind == "module-level" else inner:
            if target != "txtool" and layer_of(target) > layer_of(module):
                upward.append(f"{module} -> {target}")
    assert upward == []


def circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """Every import circle: the strongly connected components of more than one module, or of
    one that imports itself (Tarjan's algorithm, iterative), each sorted, in sorted order."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    found: list[list[str]] = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges.get(root, ()))))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, targets = work[-1]
            target = next(targets, None)
            if target is not None:
                if target not in index:
                    index[target] = low[target] = len(index)
                    stack.append(target)
                    on_stack.add(target)
                    work.append((target, iter(sorted(edges.get(target, ())))))
                elif target in on_stack:
                    low[node] = min(low[node], index[target])
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
                if len(component) > 1 or node in edges.get(node, ()):
                    found.append(sorted(component))
    return sorted(found)


def dependencies(modules: dict[str, tuple[set[str], set[str], set[str]]]) -> dict[str, set[str]]:
    """Who imports whom, in any of the three ways: at module level, inside functions, and
    under ``if TYPE_CHECKING``. A lazy import is still a dependency (the function runs sooner
    or later), and a type-checking one too: the annotation names the other module's type, and
    a type checker (and ``typing.get_type_hints``) resolves it. Hiding an import in a function
    or a type-checking block hides a circle from Python's import machinery, not from a reader.
    The package itself (``txtool``: its version only) is no module of a layer."""
    return {module: {t for t in top | typing | inner if t != "txtool"}
            for module, (top, typing, inner) in modules.items()}


def test_no_import_circle():
    """No circle, with every kind of import counted (see :func:`dependencies`), each circle
    reported with all its modules."""
    assert circles(dependencies(graph())) == []
    runtime = {module: {t for t in top | inner if t != "txtool"}
               for module, (top, _, inner) in graph().items()}
    assert circles(runtime) == []


def test_the_circle_test_finds_every_circle(tmp_path):
    """Planted circles are caught, whatever the kind of import that closes them: a
    function-level import closing a circle, a type-checking one, and two separate circles
    each reported (not only the first found)."""
    fake = tmp_path / "txtool" / "fake"
    fake.mkdir(parents=True)
    files = {
        "a": "from txtool.fake import b\n",
        "b": "def later():\n    from txtool.fake.a import something\n",
        "c": "from typing import TYPE_CHECKING\n\nif TYPE_CHECKING:\n    from txtool.fake import d\n",
        "d": "import txtool.fake.c\n",
        "e": "from txtool.fake import a\n",  # imports into a circle, is in none
    }
    for name, text in files.items():
        (fake / f"{name}.py").write_text(text)
    modules = {f"txtool.fake.{name}": imports(fake / f"{name}.py", root=tmp_path)
               for name in files}
    assert modules["txtool.fake.b"][2] == {"txtool.fake.a"}
    assert circles(dependencies(modules)) == [
        ["txtool.fake.a", "txtool.fake.b"], ["txtool.fake.c", "txtool.fake.d"]]
    assert circles({"x": {"x"}, "y": set()}) == [["x"]]


def test_the_layer_test_sees_an_upward_import(tmp_path):
    """The checker itself works: a model module importing a command is caught."""
    sample = PACKAGE / "model" / "core.py"
    assert layer_of("txtool.commands.show") > layer_of(module_name(sample))
    fake = tmp_path / "m.py"
    fake.write_text("from txtool.commands.common import fail\n")
    assert imports(fake)[0] == {"txtool.commands.common"}
    lazy = tmp_path / "lazy.py"
    lazy.write_text("def f():\n    from txtool.mechanics import linear\n")
    assert imports(lazy)[2] == {"txtool.mechanics.linear"}

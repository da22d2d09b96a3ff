"""The house's layering (docs/architecture.md), enforced over the import graph.

Every ``import`` and ``from … import`` in ``src/plumbob`` counts, including those
inside functions: a lazy import hides a cycle from Python, not from a reader.
"""

from __future__ import annotations

import ast
from pathlib import Path

import networkx as nx
import pytest
from conftest import ROOT

PACKAGE = Path(ROOT) / "src" / "plumbob"

#: Rooms from the bottom up: a room may import its own layer and the layers below it.
LAYERS: tuple[tuple[str, ...], ...] = (
    ("errors", "version", "gravity", "lazy"),
    ("units", "tolerances", "results", "plot", "report", "limits", "arguments", "frames",
     "blockwise", "callable_module", "files", "arrays"),
    ("expr", "integrals", "massprops", "materials", "loads"),
    ("mesh",),
    ("bodies",),
    ("reading",),
    ("formats",),
    ("dynamics",),
    ("spec",),
    ("loading",),
    ("stability", "energy"),
    ("export", "batch", "balance"),
    ("commands",),
    ("cli", "__main__"),
)
LAYER_OF = {room: level for level, rooms in enumerate(LAYERS) for room in rooms}


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _modules() -> dict[str, Path]:
    return {_module_name(path): path for path in sorted(PACKAGE.rglob("*.py"))}


def _imports(name: str, path: Path, modules: dict[str, Path]) -> set[str]:
    """The plumbob modules that ``name`` imports anywhere in its source."""
    package = name if path.name == "__init__.py" else name.rpartition(".")[0]
    found: set[str] = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            # `from .bodies import csg` imports the module bodies.csg, not only the package
            targets = [f"{target}.{alias.name}" if f"{target}.{alias.name}" in modules else target
                       for alias in node.names]
        else:
            continue
        for target in targets:
            while target and target not in modules:
                target = target.rpartition(".")[0]
            if target.startswith("plumbob") and target != name:
                found.add(target)
    return found


def _room(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "plumbob"


@pytest.fixture(scope="module")
def graph() -> nx.DiGraph:
    modules = _modules()
    g = nx.DiGraph()
    g.add_nodes_from(modules)
    for name, path in modules.items():
        g.add_edges_from((name, target) for target in _imports(name, path, modules))
    return g


def test_every_room_has_a_layer(graph):
    rooms = {_room(m) for m in graph} - {"plumbob"}
    unplaced = sorted(rooms - set(LAYER_OF))
    assert not unplaced, f"place these rooms in LAYERS and docs/architecture.md: {unplaced}"


def test_no_module_imports_a_higher_layer(graph):
    upward = sorted(
        f"{a} -> {b}"
        for a, b in graph.edges
        if _room(a) != "plumbob" and _room(b) != "plumbob"
        and LAYER_OF.get(_room(b), -1) > LAYER_OF.get(_room(a), -1)
    )
    assert not upward, "imports against the layering:\n" + "\n".join(upward)


def test_nothing_imports_the_package_root(graph):
    """``plumbob/__init__.py`` is the front door: rooms import each other, never it."""
    assert not [a for a, b in graph.edges if b == "plumbob"]


def test_no_import_cycle_between_modules(graph):
    cycles = [sorted(c) for c in nx.strongly_connected_components(graph) if len(c) > 1]
    assert not cycles, f"modules importing each other in a ring: {cycles}"


def test_no_import_cycle_between_rooms(graph):
    rooms = nx.DiGraph()
    rooms.add_edges_from((_room(a), _room(b)) for a, b in graph.edges if _room(a) != _room(b))
    cycles = [sorted(c) for c in nx.strongly_connected_components(rooms) if len(c) > 1]
    assert not cycles, f"rooms importing each other in a ring: {cycles}"


def test_the_graph_sees_imports_inside_functions(graph):
    """The checker itself: a lazy import in a function body is an edge too."""
    assert ("plumbob.cli", "plumbob.errors") in graph.edges
    lazy = [(a, b) for a, b in graph.edges if a.startswith("plumbob.commands") and "formats" in b]
    assert lazy or any(a.startswith("plumbob.commands") and "loading" in b for a, b in graph.edges)


def test_no_module_is_over_600_lines():
    long = {str(p.relative_to(PACKAGE)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 600}
    assert not long, f"split these modules by concern: {long}"


def _body_kinds() -> set[str]:
    """The names of the classes in ``bodies/`` that derive from ``Body`` (not ``Body`` itself)."""
    bases: dict[str, set[str]] = {}
    for path in (PACKAGE / "bodies").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef):
                bases[node.name] = {b.id if isinstance(b, ast.Name) else getattr(b, "attr", "")
                                    for b in node.bases}
    kinds: set[str] = set()
    grew = True
    while grew:
        new = {name for name, b in bases.items() if b & (kinds | {"Body"})} - kinds
        kinds |= new
        grew = bool(new)
    return kinds


def test_the_body_kinds_are_found():
    assert {"MeshSolid", "Lamina", "Assembly", "Composite", "Transformed", "GradedSolid"} <= _body_kinds()


def test_no_room_outside_bodies_switches_on_a_body_kind():
    """Rooms ask a body (the ``Body`` interface, docs/architecture.md); only ``bodies/``
    may test which kind it is."""
    kinds = _body_kinds()
    found = []
    for path in PACKAGE.rglob("*.py"):
        if (PACKAGE / "bodies") in path.parents:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (isinstance(node, ast.Call) and getattr(node.func, "id", None) in ("isinstance", "issubclass")
                    and len(node.args) == 2):
                classes = node.args[1].elts if isinstance(node.args[1], ast.Tuple) else [node.args[1]]
                names = {c.id if isinstance(c, ast.Name) else getattr(c, "attr", "") for c in classes}
                if names & kinds:
                    found.append(f"{path.relative_to(PACKAGE)}:{node.lineno} {sorted(names & kinds)}")
    assert not found, f"ask the body instead (a Body method): {found}"


#: the most lines a function's code may take (its docstring aside: a numpydoc
#: docstring with examples is documentation, not logic)
MAX_FUNCTION_LINES = 100


def _code_lines(node: ast.FunctionDef | ast.AsyncFunctionDef) -> int:
    lines = node.end_lineno - node.lineno + 1
    first = node.body[0]
    if (isinstance(first, ast.Expr) and isinstance(first.value, ast.Constant)
            and isinstance(first.value.value, str)):
        lines -= first.end_lineno - first.lineno + 1
    return lines


def test_no_function_is_over_100_lines():
    """One function, one job: a longer one is split into named steps."""
    long = [f"{path.relative_to(PACKAGE)}:{node.lineno} {node.name} ({n} lines)"
            for path in sorted(PACKAGE.rglob("*.py"))
            for node in ast.walk(ast.parse(path.read_text(encoding="utf-8")))
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
            and (n := _code_lines(node)) > MAX_FUNCTION_LINES]
    assert not long, f"split these functions into named steps: {long}"


def test_the_function_length_check_sees_a_long_function():
    """The checker itself: a 101-line body is caught, its docstring not counted."""
    body = "\n".join(f"    x{i} = {i}" for i in range(101))
    node = ast.parse(f'def f():\n    """doc\n    more"""\n{body}\n').body[0]
    assert _code_lines(node) == 102  # the def line and 101 statements


def _forged_namespaces(source: str) -> list[int]:
    """Lines that build an ``argparse.Namespace`` (``Namespace(...)``, however imported)."""
    return [node.lineno for node in ast.walk(ast.parse(source))
            if isinstance(node, ast.Call)
            and (getattr(node.func, "attr", None) == "Namespace"
                 or getattr(node.func, "id", None) == "Namespace")]


def test_no_command_forges_a_namespace():
    """A command never re-enters the CLI through a hand-built ``argparse.Namespace``:
    what two commands share is a library call (or a ``_common`` helper taking keywords)."""
    found = [f"{path.relative_to(PACKAGE)}:{line}" for path in sorted(PACKAGE.rglob("*.py"))
             for line in _forged_namespaces(path.read_text(encoding="utf-8"))]
    assert not found, f"call the library (or load_body(args, path=...)) instead: {found}"


def test_the_namespace_check_sees_a_forged_one():
    assert _forged_namespaces("import argparse\nargparse.Namespace(**vars(a))") == [2]
    assert _forged_namespaces("from argparse import Namespace\nNamespace(path=p)") == [2]


#: the most lines of logic a command module may hold: its code, the declarations of its
#: options (``add_argument`` and the like), imports, docstrings and comments aside —
#: a command parses arguments, calls the library and prints (docs/architecture.md)
MAX_COMMAND_LINES = 100
_DECLARATIONS = {"add_argument", "add_argument_group", "add_mutually_exclusive_group",
                 "add_parser", "set_defaults"}


def _logic_lines(source: str) -> int:
    import io
    import tokenize

    tree = ast.parse(source)
    aside: set[int] = set()
    for node in ast.walk(tree):
        body = getattr(node, "body", None)
        if isinstance(node, (ast.Module, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)) \
                and body and isinstance(body[0], ast.Expr) \
                and isinstance(body[0].value, ast.Constant) and isinstance(body[0].value.value, str):
            aside.update(range(body[0].lineno, body[0].end_lineno + 1))
        if (isinstance(node, ast.Call) and getattr(node.func, "attr", None) in _DECLARATIONS) \
                or isinstance(node, (ast.Import, ast.ImportFrom)):
            aside.update(range(node.lineno, node.end_lineno + 1))
        if isinstance(node, ast.Assign) and any(getattr(t, "id", None) in ("__all__", "DESCRIPTION")
                                                for t in node.targets):
            aside.update(range(node.lineno, node.end_lineno + 1))
    code: set[int] = set()
    skip = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.INDENT, tokenize.DEDENT,
            tokenize.ENDMARKER}
    for tok in tokenize.generate_tokens(io.StringIO(source).readline):
        if tok.type not in skip:
            code.update(range(tok.start[0], tok.end[0] + 1))
    return len(code - aside)


def test_no_command_module_is_over_100_lines_of_logic():
    """Text reports live in ``report/``, what a command computes in the library: a command
    module keeps to parsing, calling and printing."""
    long = {p.name: n for p in sorted((PACKAGE / "commands").glob("*.py"))
            if (n := _logic_lines(p.read_text(encoding="utf-8"))) > MAX_COMMAND_LINES}
    assert not long, f"move reports to report/ and work to the library: {long}"


def test_the_command_size_check_counts_logic_only():
    source = ('"""doc"""\nimport argparse\n\n\ndef register(p):\n    """doc\n    more"""\n'
              '    p.add_argument("--x",\n                   help="x")\n    # a comment\n'
              '    return p\n')
    assert _logic_lines(source) == 2  # the def line and the return

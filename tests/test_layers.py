"""Packages in pipeline order: no module imports from a higher layer (lazy imports included), no
import closes a loop (type-only ones included), and every module is under 400 lines."""

import ast
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1] / "src" / "rancf"

#: Layer of each top-level part of the package, in pipeline order.
LAYERS = {
    "atomic": 0,
    "errors": 0,
    "extras": 0,
    "exudyn_compat": 0,
    "options": 0,
    "geometry": 1,
    "elements": 2,
    "cad": 2,
    "kernels": 3,
    "mesh": 4,
    "bodies": 5,
    "system": 6,
    "scenario": 7,
    "solvers": 8,
    "post": 9,
    "runs": 10,
    "sweep": 11,
    "studies": 12,
    "cli": 13,
}
CLI = 13  # cli/, __main__.py, __init__.py (the lazy public API) may import anything


def _part(module: str) -> str:
    return module.split(".")[1] if module.count(".") else module


def _layer(part: str) -> int:
    return LAYERS.get(part, CLI)


def test_no_import_from_a_higher_layer():
    bad = []
    for f in sorted(ROOT.rglob("*.py")):
        rel = f.relative_to(ROOT.parent).with_suffix("")
        part = rel.parts[1] if len(rel.parts) > 1 else rel.parts[0]
        own = _layer(part.removesuffix(".py"))
        for node in ast.walk(ast.parse(f.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.ImportFrom) and node.module:
                names = [node.module]
            elif isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            for name in names:
                if name.startswith("rancf.") and _layer(_part(name)) > own:
                    bad.append(f"{'/'.join(rel.parts)} imports {name}")
    assert not bad, "\n".join(bad)


def test_every_part_has_a_layer():
    parts = {p.name for p in ROOT.iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    assert parts - {"examples"} <= set(LAYERS)


def _module_name(f: Path) -> str:
    rel = f.relative_to(ROOT.parent).with_suffix("")
    parts = rel.parts[:-1] if rel.parts[-1] == "__init__" else rel.parts
    return ".".join(parts)


def _type_only(tree: ast.AST) -> set[int]:
    """Ids of the import nodes under ``if TYPE_CHECKING:``."""
    out: set[int] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
            out.update(id(n) for b in node.body for n in ast.walk(b))
    return out


def _import_graph(type_only: bool = False) -> dict[str, set[str]]:
    """Module -> the rancf modules it imports anywhere in it (lazy imports inside functions
    included; imports under ``TYPE_CHECKING`` only with ``type_only``); ``from a import b`` names
    module ``a.b`` when ``b`` is a module."""
    files = {_module_name(f): f for f in ROOT.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for mod, f in files.items():
        out = set()
        package = mod if f.name == "__init__.py" else mod.rpartition(".")[0]
        tree = ast.parse(f.read_text(encoding="utf-8"))
        skip = set() if type_only else _type_only(tree)
        for node in ast.walk(tree):
            if id(node) in skip:
                continue
            if isinstance(node, ast.ImportFrom):
                base = node.module or ""
                if node.level:
                    up = package.split(".")[: len(package.split(".")) - node.level + 1]
                    base = ".".join(up + ([base] if base else []))
                for a in node.names:
                    sub = f"{base}.{a.name}"
                    out.add(sub if sub in files else base)
            elif isinstance(node, ast.Import):
                out.update(a.name for a in node.names)
        graph[mod] = {m for m in out if m in files and m != mod}
    return graph


def test_import_graph_has_no_cycles():
    """No module imports, at run time, one that imports it back (directly or around a loop)."""
    cycles = _cycles(_import_graph())
    assert not cycles, "\n".join(cycles)


def _cycles(graph: dict[str, set[str]]) -> list[str]:
    """The loops a depth-first walk of ``graph`` closes, as ``a -> b -> a``."""
    state: dict[str, int] = {}
    cycles = []

    def visit(m: str, stack: list[str]) -> None:
        state[m] = 1
        for n in sorted(graph[m]):
            if state.get(n) == 1:
                cycles.append(" -> ".join(stack[stack.index(n) :] + [n]))
            elif n not in state:
                visit(n, [*stack, n])
        state[m] = 2

    for m in sorted(graph):
        if m not in state:
            visit(m, [m])
    return cycles


def test_type_only_imports_have_no_cycles():
    """Not even the imports type checkers read (``if TYPE_CHECKING:``) close a loop."""
    cycles = _cycles(_import_graph(type_only=True))
    assert not cycles, "\n".join(cycles)


def test_the_cycle_finder_finds_a_cycle(tmp_path, monkeypatch):
    pkg = tmp_path / "rancf"
    pkg.mkdir()
    (pkg / "__init__.py").write_text("")
    (pkg / "a.py").write_text("from rancf.b import x\n")
    (pkg / "b.py").write_text("def f():\n    from rancf import a\n")
    monkeypatch.setattr(sys.modules[__name__], "ROOT", pkg)
    assert _import_graph()["rancf.b"] == {"rancf.a"}
    with pytest.raises(AssertionError, match="rancf.a -> rancf.b -> rancf.a"):
        test_import_graph_has_no_cycles()


#: Lines a module may have (the house's limit, "modules under 400 lines").
MAX_LINES = 400


def test_modules_under_400_lines():
    long = [
        f"{f.relative_to(ROOT)}: {n}"
        for f in sorted(ROOT.rglob("*.py"))
        if (n := len(f.read_text(encoding="utf-8").splitlines())) > MAX_LINES
    ]
    assert not long, "\n".join(long)

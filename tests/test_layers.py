"""Packages in pipeline order: no module imports from a higher layer (lazy imports included)."""

import ast
from pathlib import Path

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
    "sweep": 10,
    "studies": 11,
    "cli": 12,
}
CLI = 12  # cli/, __main__.py, __init__.py (the lazy public API) may import anything


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

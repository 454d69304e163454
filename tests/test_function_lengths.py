"""Functions stay short: Python functions in src/ at most 150 lines, C++ functions at most 200.

Python functions are measured with :mod:`ast` (decorators excluded, docstring included).  C++
functions are found by matching braces in the sources with comments and literals blanked out: a
brace block whose opening follows a parameter list ``name(...)`` (and qualifiers) and that is
not inside another function is a function body (lambdas are part of their function).
"""

from __future__ import annotations

import ast
import re
from pathlib import Path

SRC = Path(__file__).resolve().parents[1] / "src"

#: Longest Python function, in lines.
MAX_PYTHON = 150
#: Longest C++ function, in lines.
MAX_CPP = 200

_CONTROL = {"if", "for", "while", "switch", "catch", "return", "sizeof", "decltype", "alignas"}
_QUALIFIERS = re.compile(r"(\s*(const|override|noexcept|final|mutable|->\s*[\w:<>,\s*&]+))*\s*$")


def python_functions(path: Path) -> list[tuple[str, int]]:
    """Every function and method of a Python file, with its length in lines."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return [
        (node.name, node.end_lineno - node.lineno + 1)
        for node in ast.walk(tree)
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef) and node.end_lineno
    ]


def _blank(text: str) -> str:
    """C++ text with comments and string and character literals blanked (newlines kept)."""
    out, i, n = [], 0, len(text)
    while i < n:
        if text.startswith("//", i):
            j = text.find("\n", i)
            i = n if j < 0 else j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append("\n" * text.count("\n", i, j))
            i = j
        elif text[i] in "\"'":
            quote, j = text[i], i + 1
            while j < n and text[j] != quote:
                j += 2 if text[j] == "\\" else 1
            out.append(quote * 2)
            i = j + 1
        else:
            out.append(text[i])
            i += 1
    return "".join(out)


def _function_name(head: str) -> str | None:
    """The name of the function whose body opens after ``head``, or None."""
    h = _QUALIFIERS.sub("", head)
    if not h.endswith(")"):
        return None
    depth = 0
    for k in range(len(h) - 1, -1, -1):
        depth += {")": 1, "(": -1}.get(h[k], 0)
        if depth == 0:
            m = re.search(r"([~\w:]+)\s*$", h[:k])
            return m.group(1) if m and m.group(1) not in _CONTROL else None
    return None


def cpp_functions(text: str) -> list[tuple[str, int]]:
    """Every function body of a C++ source (not nested in another), with its length in lines."""
    s = _blank(text)
    out, stack = [], []
    for m in re.finditer(r"[{}]", s):
        if m.group() == "{":
            inside = any(name for name, _ in stack)
            name = None if inside else _function_name(s[max(0, m.start() - 400) : m.start()])
            stack.append((name, s.count("\n", 0, m.start())))
        elif stack:
            name, first = stack.pop()
            if name:
                out.append((name, s.count("\n", 0, m.start()) - first + 1))
    return out


def test_python_functions_short():
    long = [
        f"{key}: {n} lines"
        for f in sorted(SRC.rglob("*.py"))
        for name, n in python_functions(f)
        if n > MAX_PYTHON and (key := f"{f.relative_to(SRC)}:{name}")
    ]
    assert not long, "\n".join(long)


def test_cpp_functions_short():
    files = sorted(SRC.glob("cpp/**/*.[ch]pp"))
    assert len(files) > 20  # the scan sees the core
    long = [
        f"{f.relative_to(SRC)}:{name}: {n} lines"
        for f in files
        for name, n in cpp_functions(f.read_text(encoding="utf-8"))
        if n > MAX_CPP
    ]
    assert not long, "\n".join(long)


def test_the_scans_find_a_long_function():
    body = "\n".join(f"  x += {i};  // }} {{" for i in range(MAX_CPP + 5))
    text = (
        f"int f(int x) const {{\n  auto g = [&](int y) {{ return y; }};\n{body}\n  return x;\n}}\n"
        'struct S { int v() { return 1; } };\nconst char* s = "{";\n'
    )
    found = dict(cpp_functions(text))
    assert found["f"] > MAX_CPP and found["v"] == 1 and "g" not in found
    assert cpp_functions("void h() {\n  if (a) {\n    b();\n  }\n}\n") == [("h", 5)]


def test_the_python_scan_measures_methods(tmp_path):
    f = tmp_path / "m.py"
    f.write_text("class A:\n    def m(self):\n        return 1\n\n\ndef g():\n    pass\n")
    assert dict(python_functions(f)) == {"m": 2, "g": 2}
